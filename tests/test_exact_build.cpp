// The exact kernel's build: trees whose invariants hold when decided exactly, for every kind of
// heuristic (autopartitions, sampled scorers, cell-measuring naylor, free-plane halving), on scenes
// made to break tolerances; nothing dropped; determinism; and faults planted in a tree are caught.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "catalog.h"
#include "experiments/kernel/kernel.h"
#include "geometry/grid_plane_pool.h"
#include "geometry/snap.h"
#include "split/exact_fragments.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/exact_build.h"
#include "validate/exact_invariants.h"
#include "validate/exact_order_check.h"

using namespace bsp;

namespace {

ExactTree build_exact(const std::vector<Polygon>& polys, std::string_view heuristic, Shape shape = Shape::Strict) {
  auto splitter = make_splitter(heuristic, {}, 1);
  BuildOptions options;
  options.shape = shape;
  return build_exact_tree(polys, *splitter, options);
}

double total_area(const FragmentArray& fragments) {
  double sum = 0;
  for (const FragmentView f : fragments) sum += area(f.polygon());
  return sum;
}

void expect_valid(const ExactTree& t, const std::string& what) {
  const ExactInvariantReport r = check_exact_invariants(t);
  EXPECT_TRUE(r.ok()) << what << ": " << r.violations << " violations, first: "
                      << (r.first_problems.empty() ? "" : r.first_problems.front());
}

}  // namespace

TEST(ExactBuild, EveryKindOfHeuristicMakesTreesWhoseInvariantsHoldExactly) {
  for (const char* scene : {"random-triangles", "near-degenerate", "coplanar-heavy", "cyclic-overlap"}) {
    const Scene s = make_scene(scene, {{"n", "150"}});
    for (const char* heuristic : {"first", "random", "crystal", "naylor", "halving", "octree", "sah", "min-relation"}) {
      const ExactTree t = build_exact(s.polygons, heuristic);
      expect_valid(t, std::string(scene) + " " + heuristic);
      EXPECT_EQ(t.tree.stats.dropped_slivers, 0u);
      EXPECT_GT(t.exact.sides.predicates.filtered, 0u);
    }
    expect_valid(build_exact(s.polygons, "crystal", Shape::Coarse), std::string(scene) + " coarse");
  }
}

// The near-degenerate scene's features are 1e-9 of its diagonal: the float kernel drops slivers
// at its tolerance, the exact one keeps every piece, and the pieces cover the input's area.
TEST(ExactBuild, NearDegenerateSceneLosesNothingTheFloatKernelDrops) {
  const Scene s = make_scene("near-degenerate", {{"n", "1000"}});
  auto splitter = make_splitter("crystal", {}, 1);
  const Tree float_tree = build_tree(s.polygons, *splitter);
  EXPECT_GT(float_tree.stats.dropped_slivers + float_tree.stats.dropped_input, 0u);
  const ExactTree t = build_exact(s.polygons, "crystal");
  expect_valid(t, "near-degenerate crystal");
  EXPECT_EQ(t.tree.stats.dropped_slivers, 0u);
  EXPECT_EQ(t.exact.snap.degenerate, 0u);
  const double input = t.tree.stats.input_area;
  EXPECT_NEAR(total_area(t.tree.fragments), input, 1e-6 * input);
}

TEST(ExactBuild, SameInputSameTreeBitForBit) {
  const Scene s = make_scene("random-triangles", {{"n", "300"}, {"seed", "4"}});
  for (const char* heuristic : {"crystal", "halving"}) {
    const ExactTree a = build_exact(s.polygons, heuristic), b = build_exact(s.polygons, heuristic);
    ASSERT_EQ(a.tree.nodes.size(), b.tree.nodes.size());
    for (std::size_t i = 0; i < a.tree.nodes.size(); ++i) {
      EXPECT_EQ(a.tree.nodes[i].plane, b.tree.nodes[i].plane);
      EXPECT_EQ(a.tree.nodes[i].front, b.tree.nodes[i].front);
      EXPECT_EQ(a.tree.nodes[i].first, b.tree.nodes[i].first);
    }
    EXPECT_EQ(a.planes, b.planes);
    ASSERT_EQ(a.fragments.size(), b.fragments.size());
    for (std::size_t i = 0; i < a.fragments.size(); ++i) EXPECT_EQ(a.fragments[i].bounds, b.fragments[i].bounds);
  }
}

TEST(ExactBuild, HalvingsFreePlanesAreRoundedToGridPlanes) {
  const Scene s = make_scene("random-triangles", {{"n", "400"}});
  const ExactTree t = build_exact(s.polygons, "halving");
  EXPECT_GT(t.exact.free_planes, 10u);
  EXPECT_EQ(t.exact.free_planes_beyond, 0u);
  expect_valid(t, "halving");
}

// Faults planted in a correct tree: children swapped (fragments on the wrong side of their
// parent's plane), and the root's fragment replaced by a valid fragment of another plane (the root
// has no ancestor, so only the storage check can see it).
TEST(ExactInvariants, CatchSwappedChildrenAndAFragmentOffItsNodesPlane) {
  const Scene s = make_scene("random-triangles", {{"n", "100"}});
  const ExactTree good = build_exact(s.polygons, "crystal");
  ASSERT_TRUE(check_exact_invariants(good).ok());
  ExactTree swapped = good;
  std::uint32_t node = 0;
  while (good.tree.nodes[node].front == kNull || good.tree.nodes[node].back == kNull) ++node;
  // Flipping the node's plane swaps which side each subtree is on, and keeps the pre-order intact.
  swapped.tree.nodes[node].plane = PlanePool::flip(swapped.tree.nodes[node].plane);
  EXPECT_FALSE(check_exact_invariants(swapped).ok());
  ExactTree moved = good;
  const GridPlane root = canonical(good.plane(good.tree.nodes[0].plane));
  std::size_t other = 1;
  while (canonical(good.fragments.support(other)) == root || canonical(-good.fragments.support(other)) == root) ++other;
  ASSERT_EQ(good.tree.fragments_of(0).begin, 0u);
  ASSERT_GT(good.tree.fragments_of(0).size(), 0u);  // crystal's root plane is a fragment's
  moved.fragments.replace(0, good.fragments[other]);
  const ExactInvariantReport r = check_exact_invariants(moved);
  ASSERT_EQ(r.violations, 1u);
  EXPECT_NE(r.first_problems.front().find("not in its node's plane"), std::string::npos);
}

TEST(GridPlane, RoundedFreePlanesStayInBoundsAndNearTheirPlane) {
  const Grid grid = Grid::for_box(Box{{-3, -1, -2}, {5, 7, 1}});
  Rng rng(5);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = normalize(Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    const Vec3 through{rng.uniform(-3, 5), rng.uniform(-1, 7), rng.uniform(-2, 1)};
    const Plane p = Plane::through(n, through);
    const auto g = round_plane(p, grid);
    ASSERT_TRUE(g.has_value());
    const Int128 limit = Int128{1} << 41;
    EXPECT_TRUE(g->a < limit && g->a > -limit && g->b < limit && g->b > -limit && g->c < limit && g->c > -limit);
    const Plane back = scene_plane(*g, grid);
    EXPECT_LT(length(cross(back.n, n)), 0x1p-38);  // the normal turns by at most about 2^-39 rad
    EXPECT_LT(std::abs(back.distance(through)), 1e-11);
  }
  EXPECT_FALSE(round_plane(Plane{{1, 0, 0}, -1e20}, grid).has_value());  // beyond every grid point
}

TEST(GridPlanePool, OnePlaneMadeFromDifferentPointsHasOneIndex) {
  GridPlanePool pool(Grid::for_box(Box{{0, 0, 0}, {1, 1, 1}}));
  const auto p = plane_through({0, 0, 5}, {4, 0, 5}, {0, 4, 5});
  const auto q = plane_through({1, 1, 5}, {3, 1, 5}, {1, 3, 5});  // the same plane, a smaller normal
  const std::uint32_t i = pool.add(*p);
  EXPECT_EQ(pool.add(*q), i);
  EXPECT_EQ(pool.add(-*q), PlanePool::flip(i));
  EXPECT_EQ(pool[i], canonical(*p));
  EXPECT_EQ(pool[i].c, 1);
  EXPECT_NE(pool.add(*plane_through({0, 0, 6}, {4, 0, 6}, {0, 4, 6})) >> 1, i >> 1);
}

// canonical divides by the coefficients' greatest common divisor, also when it exceeds 64 bits.
TEST(GridPlane, CanonicalFormForgetsACommonFactor) {
  Rng rng(9);
  for (int i = 0; i < 2000; ++i) {
    // Coordinates below 2^9: normals below 2^21, offsets below 2^32; a factor below 2^94 keeps the
    // products below 2^127 and makes the common divisor wider than 64 bits.
    const auto coordinate = [&] { return static_cast<std::int64_t>(rng.below(std::uint64_t{1} << 10)) - (std::int64_t{1} << 9); };
    const auto p = plane_through({coordinate(), coordinate(), coordinate()}, {coordinate(), coordinate(), coordinate()},
                                 {coordinate(), coordinate(), coordinate()});
    if (!p) continue;
    const GridPlane c = canonical(*p);
    const Int128 k = static_cast<Int128>(1 + rng.below(std::uint64_t{1} << 60)) * static_cast<Int128>(1 + rng.below(std::uint64_t{1} << 33));
    const GridPlane scaled{c.a * k, c.b * k, c.c * k, c.d * k};
    EXPECT_EQ(canonical(scaled), c);
    EXPECT_EQ(canonical(-scaled), -c);
  }
}

// canonical against Euclid's algorithm on coefficients of every width the pool meets: small ones
// beside ones past 2^64 (the step where one number needs 128 bits and the other does not), common
// factors of any size, zeros. The result is p divided by the positive gcd of its coefficients.
TEST(GridPlane, CanonicalMatchesEuclidAtMixedWidths) {
  using U = unsigned __int128;
  const auto euclid = [](U u, U v) {
    while (v != 0) u = std::exchange(v, u % v);
    return u;
  };
  const auto mag = [](Int128 v) { return static_cast<U>(v < 0 ? -v : v); };
  Rng rng(11);
  const auto coefficient = [&] {
    const int bits = static_cast<int>(rng.below(120));  // |x| < 2^120, zero about one time in 16
    if (rng.below(16) == 0) return Int128{0};
    const U x = (static_cast<U>(rng.next()) << 64 | rng.next()) >> (127 - bits);
    return rng.below(2) ? static_cast<Int128>(x) : -static_cast<Int128>(x);
  };
  for (int i = 0; i < 20000; ++i) {
    const Int128 f = 1 + static_cast<Int128>(rng.below(std::uint64_t{1} << (rng.below(6) * 12)));
    GridPlane p{coefficient(), coefficient(), coefficient(), coefficient()};
    if (mag(p.a) < (U{1} << 100) && mag(p.b) < (U{1} << 100) && mag(p.c) < (U{1} << 100) && mag(p.d) < (U{1} << 100))
      p = {p.a * f, p.b * f, p.c * f, p.d * f};  // a common factor, kept below 2^127
    const U g = euclid(euclid(mag(p.a), mag(p.b)), euclid(mag(p.c), mag(p.d)));
    if (g == 0) continue;
    const auto k = static_cast<Int128>(g);
    ASSERT_EQ(canonical(p), (GridPlane{p.a / k, p.b / k, p.c / k, p.d / k})) << "case " << i;
  }
}

// The exact order check on the scene made to defeat tolerances: no pair in the wrong order, and
// no tie (the float kernel's check leaves thousands of pairs to its tolerance there).
TEST(ExactValidation, NearDegenerateOrdersHaveNoViolationAndNoTie) {
  const Scene s = make_scene("near-degenerate", {{"n", "300"}});
  const ExactTree t = build_exact(s.polygons, "crystal");
  ValidationSettings settings;
  settings.views = 2;
  const ExactValidationReport r = validate_exact_tree(t, settings);
  EXPECT_EQ(r.report.views, 2);
  EXPECT_GT(r.report.pairs_checked, 1000u);
  EXPECT_EQ(r.report.violations, 0u);
  EXPECT_EQ(r.report.ties(), 0u);
  EXPECT_EQ(r.eyes_beyond, 0u);
  EXPECT_GT(r.exhaustive_rays, r.report.rays / 64);
  EXPECT_EQ(r.recovered, 0u);
}

// Embree proposes from the view in doubles; a view whose fragments shrank (a planted fault standing
// for hits lost at grazing angles) loses hits near their edges, which the exhaustive search finds.
TEST(ExactValidation, RecoversHitsEmbreeDidNotPropose) {
  const Scene s = make_scene("random-triangles", {{"n", "200"}});
  ExactTree t = build_exact(s.polygons, "crystal");
  FragmentArray shrunk;
  for (Polygon p : t.tree.fragments.to_polygons()) {
    Vec3 c{0, 0, 0};
    for (const Vertex& v : p.verts) c += v.p;
    c = c * (1.0 / static_cast<double>(p.verts.size()));
    for (Vertex& v : p.verts) v.p = c + (v.p - c) * 0.8;
    shrunk.push_back(p);
  }
  t.tree.fragments = std::move(shrunk);
  ValidationSettings settings;
  settings.views = 2;
  const ExactValidationReport r = validate_exact_tree(t, settings);
  EXPECT_GT(r.recovered, 0u);
  EXPECT_EQ(r.report.violations, 0u);
}

// A node whose plane is flipped sends the traversal to the wrong side first: the check must see it.
TEST(ExactValidation, CatchesAnOrderFromAFlippedPlane) {
  const Scene s = make_scene("random-triangles", {{"n", "200"}});
  ExactTree t = build_exact(s.polygons, "crystal");
  ValidationSettings settings;
  settings.views = 2;
  ASSERT_EQ(validate_exact_tree(t, settings).report.violations, 0u);
  t.tree.nodes[0].plane = PlanePool::flip(t.tree.nodes[0].plane);
  EXPECT_GT(validate_exact_tree(t, settings).report.violations, 0u);
}

// Two unit squares overlapping in one plane, and a third far from them: the exact check counts the
// overlap's hit pairs as coplanar ties and draws no pair in the wrong order.
TEST(ExactValidation, CoplanarOverlapsAreTiesAndNothingElseIs) {
  const auto square = [](double x0, double z, std::uint32_t source) {
    return Polygon{{{{x0, 0, z}}, {{x0 + 1, 0, z}}, {{x0 + 1, 1, z}}, {{x0, 1, z}}}, source};
  };
  std::vector<Polygon> polys{square(0, 0, 0), square(0.5, 0, 1), square(3, 2, 2)};
  const ExactTree t = build_exact(polys, "first");
  ValidationSettings settings;
  settings.views = 4;
  const ExactValidationReport r = validate_exact_tree(t, settings);
  EXPECT_EQ(r.report.violations, 0u);
  EXPECT_GT(r.report.ties_coplanar, 0u);
}

// The kernel comparison on the scene made to defeat tolerances: the float kernel drops slivers,
// leaves pairs as ties and classifies some polygons differently; the exact kernel drops nothing,
// leaves no tie and draws no pair in the wrong order.
TEST(KernelComparison, NearDegenerateSceneShowsWhatTheToleranceDecides) {
  const Scene s = make_scene("near-degenerate", {{"n", "300"}});
  auto a = make_splitter("crystal", {}, 1), b = make_splitter("crystal", {}, 1);
  experiments::KernelSettings settings;
  settings.views = 2;
  const experiments::KernelComparison c = experiments::compare_kernels(s.polygons, *a, *b, settings);
  const auto& m = c.metrics;
  EXPECT_GT(m["float_dropped"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(m["exact_dropped"].get<std::uint64_t>(), 0u);
  EXPECT_GT(m["float_ties"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(m["exact_ties"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(m["exact_violations"].get<std::uint64_t>(), 0u);
  EXPECT_GT(m["classify_differences"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(c.invariants["violations"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(c.validation["violations"].get<std::uint64_t>(), 0u);
}

// Perturbing the input bends its quads within plane_eps; a bent quad's pieces have more area of
// their own than the whole's projected area, so the float tree's area check compares projections.
// This run found the check comparing the pieces' own areas (23 false violations).
TEST(KernelComparison, PerturbedInputKeepsBothTreesInvariants) {
  const Scene s = make_scene("near-degenerate", {{"n", "300"}});
  auto a = make_splitter("crystal", {}, 1), b = make_splitter("crystal", {}, 1);
  experiments::KernelSettings settings;
  settings.views = 1;
  settings.perturbation = 1e-9;
  const experiments::KernelComparison c = experiments::compare_kernels(s.polygons, *a, *b, settings);
  EXPECT_EQ(c.invariants["violations"].get<std::uint64_t>(), 0u);
  EXPECT_GT(c.metrics["snap_fanned"].get<std::uint64_t>(), 0u);  // the exact kernel saw bent quads too
}

// count_sides (blocks of planes, the box pass on each vector path, the vertex pass) counts exactly what
// classify decides one pair at a time: random triangles and their split parts against 1 to 33 of
// their own planes (odd counts, partial blocks, each fragment's own support among them).
TEST(ExactFragments, CountSidesEqualsClassifyingEachPair) {
  const Scene s = make_scene("random-triangles", {{"n", "120"}});
  SnappedScene snapped = snap_polygons(s.polygons);
  GridPlanePool pool(snapped.grid);
  ExactFragments frags(pool);
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < snapped.polygons.size(); ++i)
    ids.push_back(frags.add(snapped.polygons[i], snapped.corners[i]));
  // Split some by others' planes, so parts with new vertices (no input corners) are counted too.
  for (std::size_t i = 0; i + 1 < 40; ++i) {
    const std::uint32_t plane = frags.plane(ids[i + 1]);
    if (frags.classify(ids[i], plane) != Side::Spanning) continue;
    const auto parts = frags.split(ids[i], plane);
    ids[i] = parts.front;
    ids.push_back(parts.back);
  }
  std::vector<std::uint32_t> planes;
  for (std::size_t k = 0; k < 33; ++k) planes.push_back(frags.plane(ids[(k * 7) % ids.size()]) ^ (k & 1u));
  for (VectorPath path : {VectorPath::Widest, VectorPath::Baseline}) {
    frags.use_vector_path(path);
    const std::string on = runs_avx(path) ? "AVX " : "baseline ";
    for (std::size_t count : {1u, 2u, 3u, 4u, 5u, 31u, 32u, 33u}) {
      const std::span<const std::uint32_t> some(planes.data(), count);
      std::vector<SideCounts> counted(count);
      frags.count_sides(ids, some, counted);
      for (std::size_t j = 0; j < count; ++j) {
        SideCounts one;
        for (auto id : ids) switch (frags.classify(id, some[j])) {
            case Side::Front: ++one.front; break;
            case Side::Back: ++one.back; break;
            case Side::Coplanar: ++one.coplanar; break;
            case Side::Spanning: ++one.spanning; break;
          }
        EXPECT_EQ(counted[j].front, one.front) << on << count << " " << j;
        EXPECT_EQ(counted[j].back, one.back) << on << count << " " << j;
        EXPECT_EQ(counted[j].coplanar, one.coplanar) << on << count << " " << j;
        EXPECT_EQ(counted[j].spanning, one.spanning) << on << count << " " << j;
        EXPECT_EQ(one.front + one.back + one.coplanar + one.spanning, ids.size());
      }
    }
  }
  EXPECT_GT(frags.counters().boxes, 1000u);  // the box pass decided most pairs
}

// Broken structures are reported without walking them: a child pointing back at the root (a cycle),
// an internal node without a plane, a plane index past the pool.
TEST(ExactInvariants, BrokenStructuresAreReportedNotWalked) {
  const Scene s = make_scene("random-triangles", {{"n", "60"}});
  const ExactTree good = build_exact(s.polygons, "crystal");
  std::uint32_t node = 0;
  while (good.tree.nodes[node].front == kNull) ++node;
  ExactTree cycle = good;
  cycle.tree.nodes[cycle.tree.nodes[node].front].front = 0;
  EXPECT_FALSE(check_exact_invariants(cycle).ok());
  ExactTree planeless = good;
  planeless.tree.nodes[node].plane = kNull;
  EXPECT_FALSE(check_exact_invariants(planeless).ok());
  ExactTree beyond = good;
  beyond.tree.nodes[node].plane = static_cast<std::uint32_t>(2 * good.planes.size() + 4);
  EXPECT_FALSE(check_exact_invariants(beyond).ok());
}
