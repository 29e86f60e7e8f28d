// The splitter heuristics: known answers on inputs whose best tree is known (parallel stacks, convex
// polyhedra), the orderings their weights promise, what each one's parameters accept, and the tree
// invariants and determinism of every registered heuristic.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "catalog.h"
#include "common/errors.h"
#include "split/parallel_groups.h"
#include "search/tree_search.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/depth.h"
#include "validate/tree_invariants.h"

using namespace bsp;

namespace {

Tree build(const std::vector<Polygon>& polys, std::string_view heuristic, const ParamAssignments& params = {},
           Shape shape = Shape::Strict, std::uint64_t seed = 1) {
  auto splitter = make_splitter(heuristic, params, seed);
  return build_tree(polys, *splitter, {.shape = shape});
}

std::uint32_t ceil_log2(std::uint64_t x) {
  std::uint32_t k = 0;
  while ((std::uint64_t{1} << k) < x) ++k;
  return k;
}

Polygon quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::uint32_t source) {
  return {{{a, 0, 0}, {b, 1, 0}, {c, 1, 1}, {d, 0, 1}}, source};
}

// Unit squares facing +z at the given heights.
std::vector<Polygon> squares_at(const std::vector<double>& heights) {
  std::vector<Polygon> out;
  for (double z : heights)
    out.push_back(quad({0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}, static_cast<std::uint32_t>(out.size())));
  return out;
}

std::vector<Polygon> stacked_squares(std::size_t n) {
  std::vector<double> z(n);
  for (std::size_t i = 0; i < n; ++i) z[i] = static_cast<double>(i);
  return squares_at(z);
}

// A vertical wall in the plane x = 0.5 over z in [z0, z1], facing +x.
Polygon wall(double z0, double z1, std::uint32_t source) {
  return quad({0.5, 0, z0}, {0.5, 1, z0}, {0.5, 1, z1}, {0.5, 0, z1}, source);
}

// A geodesic sphere: the icosahedron with each triangle cut into four `level` times, vertices pushed
// onto the unit sphere: 20 * 4^level faces, a convex polyhedron. Faces are counter-clockwise seen
// from outside (each face's plane has all the others behind it), or from inside when `inward`.
std::vector<Polygon> geodesic_sphere(int level, bool inward) {
  const double g = std::numbers::phi;
  const std::array<Vec3, 12> v = {{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                   {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  std::vector<std::array<Vec3, 3>> tris;
  for (const auto& f : faces) tris.push_back({normalize(v[f[0]]), normalize(v[f[1]]), normalize(v[f[2]])});
  for (int l = 0; l < level; ++l) {
    std::vector<std::array<Vec3, 3>> finer;
    for (const auto& [a, b, c] : tris) {
      const Vec3 ab = normalize(a + b), bc = normalize(b + c), ca = normalize(c + a);
      finer.push_back({a, ab, ca});
      finer.push_back({ab, b, bc});
      finer.push_back({ca, bc, c});
      finer.push_back({ab, bc, ca});
    }
    tris = std::move(finer);
  }
  std::vector<Polygon> out;
  for (auto [a, b, c] : tris) {
    const bool outward = dot(cross(b - a, c - a), a + b + c) > 0;
    if (outward == inward) std::swap(b, c);
    out.push_back({{{a, 0, 0}, {b, 1, 0}, {c, 0, 1}}, static_cast<std::uint32_t>(out.size())});
  }
  return out;
}

std::vector<std::string> heuristic_names(bool autopartition_only) {
  std::vector<std::string> names;
  for (const auto& h : heuristics())
    if (h.autopartition || !autopartition_only) names.push_back(h.name);
  return names;
}

// Bit for bit: the same nodes, plane indices, pooled planes, fragments and build counts.
bool identical(const Tree& a, const Tree& b) {
  if (a.nodes.size() != b.nodes.size() || a.fragments.size() != b.fragments.size() ||
      a.planes.size() != b.planes.size() || a.fragment_plane != b.fragment_plane)
    return false;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const Node &x = a.nodes[i], &y = b.nodes[i];
    if (x.front != y.front || x.back != y.back || x.first != y.first || x.plane != y.plane)
      return false;
  }
  for (std::uint32_t i = 0; i < a.planes.size(); ++i)
    if (!(a.planes[i] == b.planes[i])) return false;
  for (std::size_t i = 0; i < a.fragments.size(); ++i) {
    const Polygon p = a.fragments[i].polygon(), q = b.fragments[i].polygon();
    if (p.source != q.source || p.verts.size() != q.verts.size()) return false;
    for (std::size_t v = 0; v < p.verts.size(); ++v)
      if (!(p.verts[v].p == q.verts[v].p) || p.verts[v].u != q.verts[v].u || p.verts[v].v != q.verts[v].v) return false;
  }
  const BuildStats &s = a.stats, &t = b.stats;
  return s.splits == t.splits && s.dropped_input == t.dropped_input && s.dropped_slivers == t.dropped_slivers &&
         s.dropped_area == t.dropped_area && s.input_area == t.input_area && s.fallbacks == t.fallbacks;
}

// The root's plane as the height of a z-plane (the test scenes put it there).
double root_height(const Tree& tree) {
  const Plane& p = tree.planes[tree.nodes[0].plane];
  EXPECT_NEAR(std::abs(p.n.z), 1.0, 1e-12);
  return -p.d / p.n.z;
}

}  // namespace

// --- known answers ----------------------------------------------------------------------------

TEST(BalancedKnownAnswer, StackedSquaresGiveMinimalDepthAndNoSplits) {
  for (std::size_t n : {1, 2, 3, 7, 8, 31, 100}) {
    for (const char* h : {"balanced", "min-relation"}) {
      const Tree tree = build(stacked_squares(n), h);
      EXPECT_EQ(max_depth(tree), ceil_log2(n + 1)) << h << " n=" << n;
      EXPECT_EQ(tree.stats.splits, 0u) << h << " n=" << n;
      EXPECT_EQ(tree.nodes.size(), n) << h << " n=" << n;
    }
    // The baseline on the same input is a chain: the check above can fail.
    EXPECT_EQ(max_depth(build(stacked_squares(n), "first")), n);
  }
}

TEST(HalvingKnownAnswer, StackedSquaresAreHalvedByFreePlanesInTheGapsWithoutSplits) {
  for (std::size_t n : {2, 5, 8, 64, 100}) {
    const Tree tree = build(stacked_squares(n), "halving");
    EXPECT_EQ(tree.stats.splits, 0u) << n;
    EXPECT_EQ(tree.stats.fallbacks, 0u) << n;
    // Free planes down to one square per cell, then one node holding it.
    EXPECT_EQ(max_depth(tree), ceil_log2(n) + 1) << n;
    EXPECT_EQ(tree.fragments_of(0).size(), 0u) << "the root is a free plane through no square";
  }
}

TEST(HalvingKnownAnswer, PrefersAGapNearTheMedianOverACutAtIt) {
  // Ten squares at z = 0..9 and a wall across z in [3.5, 5.5]: the plane z = 4.5 is perfectly
  // balanced but cuts the wall; z = 3.25 and z = 5.75 are gaps three fragments off balance.
  auto polys = stacked_squares(10);
  polys.push_back(wall(3.5, 5.5, 10));
  const Tree strict_median = build(polys, "halving", {{"balance_slack", "0.1"}});
  EXPECT_NEAR(root_height(strict_median), 4.5, 1e-12);
  const Tree gap = build(polys, "halving", {{"balance_slack", "0.3"}});
  EXPECT_NEAR(root_height(gap), 3.25, 1e-12);
}

TEST(HalvingKnownAnswer, FallsBackWhenNoPlaneParallelToThePolygonsSeparatesThem) {
  // Two squares crossing in an X: every place parallel to either leaves a side with nothing whole.
  const std::vector<Polygon> polys = {quad({0, 0, 0.5}, {1, 0, 0.5}, {1, 1, 0.5}, {0, 1, 0.5}, 0), wall(0, 1, 1)};
  const Tree tree = build(polys, "halving");
  EXPECT_NEAR(root_height(tree), 0.5, 1e-12) << "balanced fallback takes the first square's own plane";
  EXPECT_EQ(tree.fragments_of(0).size(), 1u);
  EXPECT_EQ(tree.stats.fallbacks, 0u);
}

TEST(MinRelationKnownAnswer, RelationThresholdTradesBalanceForSplits) {
  // Seven squares at z = 0..6 and a wall across z in [2.5, 3.5]: only z = 3 is balanced (relation 1)
  // and it cuts the wall; z = 2 and z = 4 split nothing at relation 2/5.
  auto polys = stacked_squares(7);
  polys.push_back(wall(2.5, 3.5, 7));
  EXPECT_NEAR(root_height(build(polys, "min-relation", {{"min_relation", "0.8"}})), 3.0, 1e-12);
  EXPECT_NEAR(root_height(build(polys, "min-relation", {{"min_relation", "0.3"}})), 2.0, 1e-12);
  // From 1 nothing qualifies; halving the threshold reaches 0.5 (only z = 3), quartering it 0.25.
  EXPECT_NEAR(root_height(build(polys, "min-relation", {{"min_relation", "1"}})), 3.0, 1e-12);
  EXPECT_NEAR(root_height(build(polys, "min-relation", {{"min_relation", "1"}, {"min_relation_scale", "4"}})),
              2.0, 1e-12);
}

TEST(NaylorKnownAnswer, CutsADenseClusterOffTheLargeEmptyCell) {
  // Ten squares packed in z in [0, 0.09] and one at z = 10. Balance says the median (z = 0.05);
  // the expected cost says to wall off the cluster, whose cell a query rarely enters (z = 0.09).
  std::vector<double> z;
  for (int i = 0; i < 10; ++i) z.push_back(0.01 * i);
  z.push_back(10);
  const auto polys = squares_at(z);
  EXPECT_NEAR(root_height(build(polys, "balanced")), 0.05, 1e-12);
  for (const char* model : {"volume", "area"})
    EXPECT_NEAR(root_height(build(polys, "naylor", {{"model", model}})), 0.09, 1e-12) << model;
}

TEST(QuakeKnownAnswer, CoplanarAndAxialBonusesOutweighBalance) {
  // A tilted square T between two squares lying in z = 0 and one square at z = 3. T's plane leaves
  // 2 fragments behind and 1 in front (imbalance 1); the plane z = 0 holds 2 squares, is axial,
  // and leaves the other 2 in front (imbalance 2). Nothing is split either way. Quake's bonuses
  // (5 per coplanar fragment, 5 for axial) take z = 0; the same split and balance weights without
  // them take T.
  const std::vector<Polygon> polys = {quad({0, 0, 1}, {1, 0, 1.5}, {1, 1, 1.5}, {0, 1, 1}, 0),
                                      quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 1),
                                      quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, 2),
                                      quad({0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}, 3)};
  const Tree quake = build(polys, "quake");
  EXPECT_NEAR(root_height(quake), 0.0, 1e-12);
  EXPECT_EQ(quake.fragments_of(0).size(), 2u);
  const Tree plain = build(polys, "weighted", {{"split_weight", "5"}, {"balance_weight", "1"}});
  EXPECT_EQ(plain.fragments[plain.nodes[0].first].source, 0u);
}

// --- convex polyhedra ----------------------------------------------------------------------------

TEST(ConvexPolyhedron, EveryAutopartitionOfAnOutwardSphereIsAChainAsDeepAsItsFaces) {
  const auto sphere = geodesic_sphere(2, false);
  ASSERT_EQ(sphere.size(), 320u);
  for (const auto& name : heuristic_names(true)) {
    const Tree tree = build(sphere, name);
    EXPECT_EQ(max_depth(tree), sphere.size()) << name;
    EXPECT_EQ(tree.stats.splits, 0u) << name;
  }
}

TEST(ConvexPolyhedron, AnInwardSphereIsOneCoarseLeafForEveryHeuristic) {
  const auto sphere = geodesic_sphere(2, true);
  for (const auto& name : heuristic_names(false)) {
    const Tree coarse = build(sphere, name, {}, Shape::Coarse);
    ASSERT_EQ(coarse.nodes.size(), 1u) << name;
    EXPECT_TRUE(coarse.nodes[0].is_cell_leaf()) << name;
    EXPECT_EQ(coarse.fragments_of(0).size(), sphere.size()) << name;
  }
  // The same faces turned outward are no convex set: the check above can fail.
  EXPECT_GT(build(geodesic_sphere(2, false), "first", {}, Shape::Coarse).nodes.size(), 1u);
}

TEST(ConvexPolyhedron, HalvingDepthOnASphereGrowsLogarithmically) {
  // Measured: 80 faces -> depth 14, 320 -> 17, 1280 -> 19, 5120 -> 22, about 1.3 log2(faces) + 6,
  // where every autopartition makes a chain as deep as the face count. Each fourfold resolution
  // adds a few levels, and the depth stays under 2.5 log2(faces).
  const std::array<std::uint32_t, 4> expected = {14, 17, 19, 22};
  std::uint32_t previous = 0;
  for (int level = 1; level <= 4; ++level) {
    const auto sphere = geodesic_sphere(level, false);
    const Tree tree = build(sphere, "halving");
    const std::uint32_t depth = max_depth(tree);
    EXPECT_EQ(depth, expected[level - 1]) << sphere.size() << " faces";
    EXPECT_LE(depth, 2.5 * std::log2(static_cast<double>(sphere.size()))) << sphere.size() << " faces";
    if (previous) {
      EXPECT_LE(depth - previous, 4u) << sphere.size() << " faces";
    }
    previous = depth;
    EXPECT_TRUE(check_tree_invariants(tree, sphere).ok());
  }
}

// --- orderings ----------------------------------------------------------------------------------

TEST(WeightedOrdering, SplitWeightSplitsLessAndBalanceWeightBuildsShallower) {
  double split_only_splits = 0, balance_only_splits = 0, split_only_depth = 0, balance_only_depth = 0;
  for (int seed = 1; seed <= 4; ++seed) {
    const Scene scene = make_scene("random-triangles", {{"n", "300"}, {"seed", std::to_string(seed)}});
    const Tree s = build(scene.polygons, "weighted", {{"split_weight", "1"}, {"balance_weight", "0"}});
    const Tree b = build(scene.polygons, "weighted", {{"split_weight", "0"}, {"balance_weight", "1"}});
    split_only_splits += s.stats.splits;
    balance_only_splits += b.stats.splits;
    split_only_depth += max_depth(s);
    balance_only_depth += max_depth(b);
  }
  EXPECT_LT(split_only_splits, balance_only_splits);
  EXPECT_LT(balance_only_depth, split_only_depth);
}

// The SAH's binned counts against a count by brute force [Wald2007]: at the root of random
// triangles, the plane taken is the cheapest bin bound that parts the fragments and costs less than
// a leaf, where n(L) counts the fragments starting below the bound and n(R) those ending above it.
// An off-by-one in a bin's start or end count changes some bound's cost and, on some scene, the choice.
TEST(Sah, RootPlaneIsTheCheapestBinBoundCountedByBruteForce) {
  constexpr std::size_t kBins = 16;          // sah's defaults
  constexpr double kTraversalCost = 1;
  int cut = 0;
  for (int seed = 1; seed <= 12; ++seed) {
    const Scene scene = make_scene("random-triangles", {{"n", "120"}, {"seed", std::to_string(seed)}});
    const Tree t = build(scene.polygons, "sah", {{"leaf_faces", "8"}});
    std::vector<Box> boxes;
    Box all;
    for (const Polygon& poly : scene.polygons) {
      Box b;
      for (const Vertex& v : poly.verts) b.add(v.p);
      boxes.push_back(b);
      all.add(b);
    }
    const double eps = t.tol.plane_eps;
    const Vec3 size = all.size();
    const auto area = [](const Vec3& e) { return 2 * (e.x * e.y + e.y * e.z + e.z * e.x); };
    std::tuple<double, int, double> best{std::numeric_limits<double>::infinity(), 0, 0};
    for (int axis = 0; axis < 3; ++axis)
      for (std::size_t k = 1; k < kBins; ++k) {
        const double x = all.lo[axis] + size[axis] * static_cast<double>(k) / static_cast<double>(kBins);
        std::size_t below = 0, above = 0, behind = 0, ahead = 0;
        for (const Box& b : boxes) {
          below += b.lo[axis] < x;
          above += b.hi[axis] > x;
          behind += b.hi[axis] < x - eps;
          ahead += b.lo[axis] > x + eps;
        }
        Vec3 lower = size, upper = size;
        (axis == 0 ? lower.x : axis == 1 ? lower.y : lower.z) = x - all.lo[axis];
        (axis == 0 ? upper.x : axis == 1 ? upper.y : upper.z) = all.hi[axis] - x;
        const double cost = kTraversalCost + (area(lower) * static_cast<double>(below) + area(upper) * static_cast<double>(above)) / area(size);
        if (behind > 0 && ahead > 0 && cost < static_cast<double>(boxes.size())) best = std::min(best, {cost, axis, x});
      }
    ASSERT_FALSE(t.empty());
    const Plane root = t.planes[t.nodes[0].plane];
    if (std::isinf(std::get<0>(best))) continue;  // no bound pays: the faces' own planes from the root
    ++cut;
    const int axis = std::get<1>(best);
    const Vec3 n{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
    const bool flipped = dot(root.n, n) < 0;
    EXPECT_EQ(flipped ? root.n * -1.0 : root.n, n) << "seed " << seed;
    EXPECT_EQ(flipped ? root.d : -root.d, std::get<2>(best)) << "seed " << seed;  // sah.cpp's arithmetic
  }
  EXPECT_GE(cut, 10);
}

// --- parallel groups ----------------------------------------------------------------------------

TEST(ParallelGroups, OppositeFacingsAndNormalsWithinTheToleranceShareAGroup) {
  const double tol = 1e-3;
  const Vec3 z{0, 0, 1};
  const Vec3 tilted_in = normalize(Vec3{0.5 * tol, 0, 1});   // within the tolerance
  const Vec3 tilted_out = normalize(Vec3{2.0 * tol, 0, 1});  // beyond it
  const std::vector<Vec3> normals = {z, -z, tilted_in, -tilted_in, tilted_out, {1, 0, 0}, z};
  const ParallelGroups g = group_parallel(normals, tol);
  EXPECT_EQ(g.group_of, (std::vector<std::uint32_t>{0, 0, 0, 0, 1, 2, 0}));
  EXPECT_EQ(g.size, (std::vector<std::uint32_t>{5, 1, 1}));
}

// --- parameters ---------------------------------------------------------------------------------

TEST(HeuristicParams, UnknownKeysAndOutOfRangeValuesAreRejected) {
  for (const auto& h : heuristics()) {
    EXPECT_NO_THROW(make_splitter(h.name, {}, 1)) << h.name;
    EXPECT_THROW(make_splitter(h.name, {{"no_such_parameter", "1"}}, 1), UsageError) << h.name;
    for (const auto& spec : h.params) {
      if (spec.kind == ParamSpec::Kind::Choice) {
        EXPECT_THROW(make_splitter(h.name, {{spec.name, "no-such-choice"}}, 1), UsageError) << h.name;
        for (const auto& c : spec.choices) EXPECT_NO_THROW(make_splitter(h.name, {{spec.name, c}}, 1)) << h.name;
        continue;
      }
      ASSERT_TRUE(spec.min > -1e300 && spec.max < 1e300) << h.name << "." << spec.name << " has no finite range";
      EXPECT_THROW(make_splitter(h.name, {{spec.name, std::to_string(spec.max * 2 + 1)}}, 1), UsageError)
          << h.name << "." << spec.name;
      EXPECT_THROW(make_splitter(h.name, {{spec.name, std::to_string(spec.min - 1)}}, 1), UsageError)
          << h.name << "." << spec.name;
      EXPECT_THROW(make_splitter(h.name, {{spec.name, "x"}}, 1), UsageError) << h.name << "." << spec.name;
    }
  }
}

TEST(HeuristicParams, FreePlaneFallbacksAreRegisteredAutopartitions) {
  for (const char* name : {"halving", "octree", "sah"}) {
    const auto& h = find_heuristic(name);
    EXPECT_FALSE(h.autopartition) << name;
    const auto fallback =
        std::find_if(h.params.begin(), h.params.end(), [](const ParamSpec& s) { return s.name == "fallback"; });
    ASSERT_NE(fallback, h.params.end()) << name;
    for (const auto& f : fallback->choices) EXPECT_TRUE(find_heuristic(f).autopartition) << name << " " << f;
  }
}

TEST(HeuristicCatalog, JsonListsEveryHeuristicWithItsParametersAndDefaults) {
  FILE* pipe = popen(BSPBENCH_EXE " heuristics --json", "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  std::array<char, 4096> buf;
  while (const std::size_t got = fread(buf.data(), 1, buf.size(), pipe)) text.append(buf.data(), got);
  ASSERT_EQ(pclose(pipe), 0);
  const auto list = nlohmann::json::parse(text);
  // The heuristics, then the searching builders, which take names and parameters alike.
  std::vector<HeuristicInfo> all(heuristics().begin(), heuristics().end());
  for (const auto& s : searches()) all.push_back({s.name, s.summary, s.params, true, {}});
  ASSERT_EQ(list.size(), all.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto& h = all[i];
    EXPECT_EQ(list[i]["name"], h.name);
    EXPECT_EQ(list[i]["autopartition"], h.autopartition);
    ASSERT_EQ(list[i]["params"].size(), h.params.size()) << h.name;
    for (std::size_t j = 0; j < h.params.size(); ++j) {
      const auto& p = list[i]["params"][j];
      EXPECT_EQ(p["name"], h.params[j].name) << h.name;
      if (h.params[j].kind == ParamSpec::Kind::Choice)
        EXPECT_EQ(p["default"], h.params[j].choices.front()) << h.name;
      else
        EXPECT_DOUBLE_EQ(p["default"].get<double>(), h.params[j].default_value) << h.name;
    }
  }
}

// --- every heuristic ----------------------------------------------------------------------------

class RegisteredHeuristic : public ::testing::TestWithParam<std::string> {};

TEST_P(RegisteredHeuristic, TreeInvariantsHoldOnSoupsAndCyclesInBothShapes) {
  for (const char* scene_name : {"random-triangles", "cyclic-overlap"}) {
    const Scene scene = make_scene(scene_name, {{"n", "300"}, {"seed", "5"}});
    for (Shape shape : {Shape::Strict, Shape::Coarse}) {
      const Tree tree = build(scene.polygons, GetParam(), {}, shape);
      const InvariantReport report = check_tree_invariants(tree, scene.polygons);
      EXPECT_TRUE(report.ok()) << scene_name << (shape == Shape::Coarse ? " coarse: " : " strict: ")
                               << report.violations << " violations, first: "
                               << (report.first_problems.empty() ? "" : report.first_problems.front());
    }
  }
}

TEST_P(RegisteredHeuristic, SameSeedGivesTheSameTreeBitForBit) {
  const Scene scene = make_scene("random-triangles", {{"n", "300"}, {"seed", "9"}});
  EXPECT_TRUE(identical(build(scene.polygons, GetParam(), {}, Shape::Strict, 42),
                        build(scene.polygons, GetParam(), {}, Shape::Strict, 42)));
}

// Handing subtrees to tasks and running those on two threads changes nothing: the tree built with
// many small tasks on one and on two threads equals, bit for bit, the tree built with none.
TEST_P(RegisteredHeuristic, TasksAndThreadsLeaveTheTreeBitForBit) {
  const int threads = omp_get_max_threads();
  for (const char* scene_name : {"random-triangles", "architecture"}) {
    const Scene scene = make_scene(scene_name, {{"n", "600"}, {"seed", "3"}});
    for (Shape shape : {Shape::Strict, Shape::Coarse}) {
      const auto splitter = make_splitter(GetParam(), {}, 7);
      const BuildOptions none{.shape = shape, .min_task_fragments = std::numeric_limits<std::size_t>::max()};
      const BuildOptions many{.shape = shape, .task_share = 4, .min_task_fragments = 8};
      omp_set_num_threads(1);
      const Tree whole = build_tree(scene.polygons, *splitter, none);
      const Tree tasks_one_thread = build_tree(scene.polygons, *splitter, many);
      omp_set_num_threads(2);
      const Tree tasks_two_threads = build_tree(scene.polygons, *splitter, many);
      EXPECT_EQ(whole.stats.tasks, 0u);
      EXPECT_GT(tasks_one_thread.stats.tasks, 3u) << scene_name;
      EXPECT_TRUE(identical(whole, tasks_one_thread)) << scene_name << (shape == Shape::Coarse ? " coarse" : " strict");
      EXPECT_TRUE(identical(whole, tasks_two_threads)) << scene_name << (shape == Shape::Coarse ? " coarse" : " strict");
    }
  }
  omp_set_num_threads(threads);
}

INSTANTIATE_TEST_SUITE_P(Registry, RegisteredHeuristic, ::testing::ValuesIn(heuristic_names(false)),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(SampledHeuristics, TheSeedChoosesTheSampleAndOnlyThen) {
  const Scene scene = make_scene("random-triangles", {{"n", "300"}, {"seed", "9"}});
  for (const char* h : {"crystal", "naylor", "weighted", "quake", "balanced", "min-relation"})
    EXPECT_FALSE(identical(build(scene.polygons, h, {}, Shape::Strict, 1), build(scene.polygons, h, {}, Shape::Strict, 2)))
        << h;
  // Scoring every candidate against every fragment (candidates = 0, sample = 0) leaves nothing to chance.
  const ParamAssignments exhaustive = {{"candidates", "0"}};
  for (const char* h : {"weighted", "quake", "balanced", "min-relation"})
    EXPECT_TRUE(identical(build(scene.polygons, h, exhaustive, Shape::Strict, 1),
                          build(scene.polygons, h, exhaustive, Shape::Strict, 2)))
        << h;
  // A counted sample is drawn from the seed too, even when every candidate is scored.
  const ParamAssignments sampled_counts = {{"candidates", "0"}, {"sample", "20"}};
  EXPECT_FALSE(identical(build(scene.polygons, "weighted", sampled_counts, Shape::Strict, 1),
                         build(scene.polygons, "weighted", sampled_counts, Shape::Strict, 2)));
  // A sample as large as the node is the node: the same tree as exact counts, whatever the seed.
  const ParamAssignments whole_sample = {{"candidates", "0"}, {"sample", "1000000"}};
  EXPECT_TRUE(identical(build(scene.polygons, "weighted", whole_sample, Shape::Strict, 2),
                        build(scene.polygons, "weighted", exhaustive, Shape::Strict, 1)));
}

// A splitter's clone (what a task builds with) chooses as a fresh splitter does, whatever the
// original chose before: naylor keeps the cells of its previous node's path by pooled plane index,
// and a task numbers its planes in a pool of its own, where the original's indices name other
// planes. Here the same fragments are pooled in opposite orders, so cell plane indices {0, 2, ...}
// name different planes in the two pools.
TEST(NaylorSplitter, ACloneChoosesAsAFreshSplitterDoesWhateverTheOriginalChoseBefore) {
  const Scene scene = make_scene("random-triangles", {{"n", "200"}, {"seed", "5"}});
  Box box;
  for (const Polygon& p : scene.polygons)
    for (const Vertex& v : p.verts) box.add(v.p);
  const Tolerance tol = Tolerance::for_extent(box.diagonal());
  struct Pooled {
    FragmentStore frags;
    PlanePool planes;
    std::vector<std::uint32_t> ids;
  };
  const auto pool = [&](bool reversed) {
    Pooled out;
    std::vector<std::size_t> order(scene.polygons.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = reversed ? order.size() - 1 - i : i;
    for (std::size_t i : order)
      if (const auto plane = supporting_plane(scene.polygons[i]))
        out.ids.push_back(out.frags.add(scene.polygons[i], out.planes.add(*plane)));
    return out;
  };
  const Pooled forward = pool(false), backward = pool(true);
  const auto context = [&](const Pooled& p, std::span<const std::uint32_t> cell) {
    return SplitContext{p.ids, p.frags, p.planes, tol, box, cell, static_cast<std::uint32_t>(cell.size() + 1)};
  };
  int differing_cells = 0;
  for (std::uint32_t depth = 1; depth <= 4; ++depth) {
    std::vector<std::uint32_t> cell;
    for (std::uint32_t k = 0; k < depth; ++k) cell.push_back(2 * k);
    const auto original = make_splitter("naylor", {}, 3);
    original->choose(context(forward, cell));
    const auto clone = original->clone();
    const auto fresh = make_splitter("naylor", {}, 3);
    const SplitChoice a = clone->choose(context(backward, cell)), b = fresh->choose(context(backward, cell));
    EXPECT_EQ(a.fragment, b.fragment) << "cell of " << depth << " planes";
    differing_cells += !(forward.planes[cell.back()] == backward.planes[cell.back()]);
  }
  EXPECT_EQ(differing_cells, 4);  // the indices named other planes in the other pool
}
