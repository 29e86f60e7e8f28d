// Tree-quality metrics: shape metrics and Naylor's expected costs pinned on hand-built trees, the
// exact expected costs against Monte Carlo estimates, frustum culling that never loses a fragment in
// view, ray shooting against brute force and against Embree for every registered heuristic, the
// statistics of `bspbench compare`, and the command itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <sys/wait.h>

#include "catalog.h"
#include "common/rng.h"
#include "metrics/expected_cost.h"
#include "metrics/ray_cost.h"
#include "tree/ray_shoot.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "metrics/tree_metrics.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse_culled.h"
#include "validate/embree_scene.h"
#include "validate/ray_shoot_check.h"
#include "validate/view_rays.h"

using namespace bsp;

namespace {

Tree build(const std::vector<Polygon>& polys, std::string_view heuristic, BuildOptions opts = {}) {
  auto splitter = make_splitter(heuristic, {}, 1);
  return build_tree(polys, *splitter, opts);
}

Tree build_scene(std::string_view scene, int n, std::string_view heuristic, BuildOptions opts = {}) {
  return build(make_scene(scene, {{"n", std::to_string(n)}, {"seed", "3"}}).polygons, heuristic, opts);
}

// --- hand-built trees in the unit cube

Vec3 axis_vector(int axis) { return {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0}; }

// A square in the plane x_axis = value covering [0.1, 0.4]^2 of the other two axes, counter-
// clockwise about +axis.
Polygon axis_square(int axis, double value) {
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  Polygon p;
  for (auto [u, v] : {std::pair{0.1, 0.1}, {0.4, 0.1}, {0.4, 0.4}, {0.1, 0.4}}) {
    double c[3];
    c[axis] = value;
    c[a] = u;
    c[b] = v;
    p.verts.push_back({{c[0], c[1], c[2]}, 0, 0});
  }
  return p;
}

struct HandNode {
  int axis;  // plane x_axis = 0.5, front towards +axis
  std::uint32_t front, back;
  int fragments;  // squares stored on the plane
};

// Nodes must be listed in pre-order. Bounds: the unit cube.
Tree hand_built(const std::vector<HandNode>& spec) {
  Tree t;
  t.bounds.add(Vec3{0, 0, 0});
  t.bounds.add(Vec3{1, 1, 1});
  t.tol = Tolerance::for_extent(t.bounds.diagonal());
  for (const HandNode& s : spec) {
    Node n;
    n.plane = t.planes.add(Plane{axis_vector(s.axis), -0.5});
    n.front = s.front;
    n.back = s.back;
    n.first = static_cast<std::uint32_t>(t.fragments.size());
    for (int i = 0; i < s.fragments; ++i) {
      t.fragments.push_back(axis_square(s.axis, 0.5));
      t.fragment_plane.push_back(n.plane);
    }
    t.nodes.push_back(n);
  }
  t.stats.n_input = t.fragments.size();
  return t;
}

// Root x = 0.5 (1 square); its front child y = 0.5 (2 squares) with front child z = 0.5 (1); its
// back child y = 0.5 (1). Pre-order: root 0, front 1, front-front 2, back 3.
Tree four_node_tree() { return hand_built({{0, 1, 3, 1}, {1, 2, kNull, 2}, {2, kNull, kNull, 1}, {1, kNull, kNull, 1}}); }

// --- Monte Carlo estimates of the expected costs, independent of the polytopes

Vec3 sphere_direction(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double monte_carlo_e_point(const Tree& tree, const Box& root, int samples) {
  Rng rng(11);
  double sum = 0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 p{rng.uniform(root.lo.x, root.hi.x), rng.uniform(root.lo.y, root.hi.y), rng.uniform(root.lo.z, root.hi.z)};
    sum += point_plane_tests(tree, p);  // the measured cost's walk, checked against the exact model
  }
  return sum / samples;
}

// The parameter interval of the line o + t d inside the box; empty (t0 > t1) when it misses.
std::pair<double, double> line_in_box(const Vec3& o, const Vec3& d, const Box& box) {
  double t0 = -1e300, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    const double ta = (box.lo[a] - o[a]) / d[a], tb = (box.hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return {t0, t1};
}

// Nodes whose cell the segment o + t d, t in [t0, t1], crosses: walk the segment down the tree.
std::uint32_t nodes_crossed(const Tree& tree, const Vec3& o, const Vec3& d, double t0, double t1) {
  struct Item {
    std::uint32_t node;
    double a, b;
  };
  std::vector<Item> stack{{0, t0, t1}};
  std::uint32_t count = 0;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    ++count;
    const Node& node = tree.nodes[it.node];
    if (node.is_cell_leaf()) continue;
    const Plane& pl = tree.planes[node.plane];
    const double da = pl.distance(o + d * it.a), db = pl.distance(o + d * it.b);
    const double tc = da * db < 0 ? it.a + (it.b - it.a) * da / (da - db) : it.b;
    const std::uint32_t at_a = da >= 0 ? node.front : node.back, at_b = da >= 0 ? node.back : node.front;
    if (at_a != kNull) stack.push_back({at_a, it.a, tc});
    if (tc < it.b && at_b != kNull) stack.push_back({at_b, tc, it.b});
  }
  return count;
}

// Lines from the isotropic uniform line measure restricted to those meeting the box: a uniform
// direction, then a uniform point of the disc of radius half the diagonal perpendicular to it
// through the box centre (it holds the box's whole projection); lines missing the box are redrawn.
double monte_carlo_e_line(const Tree& tree, const Box& root, int samples) {
  Rng rng(12);
  const double r = root.diagonal() / 2;
  double sum = 0;
  for (int accepted = 0; accepted < samples;) {
    const Vec3 d = sphere_direction(rng);
    const Vec3 e1 = normalize(std::abs(d.x) < 0.9 ? cross(d, Vec3{1, 0, 0}) : cross(d, Vec3{0, 1, 0}));
    const Vec3 e2 = cross(d, e1);
    const double a = rng.uniform(-1.0, 1.0), b = rng.uniform(-1.0, 1.0);
    if (a * a + b * b > 1) continue;
    const Vec3 o = root.center() + (e1 * a + e2 * b) * r;
    const auto [t0, t1] = line_in_box(o, d, root);
    if (t0 >= t1) continue;
    ++accepted;
    sum += nodes_crossed(tree, o, d, t0, t1);
  }
  return sum / samples;
}

// --- ray shooting references

std::optional<RayHit> brute_force_first_hit(const Tree& tree, const Ray& ray) {
  std::optional<RayHit> best;
  for (std::uint32_t i = 0; i < tree.fragments.size(); ++i) {
    const auto t = ray_polygon_hit(ray, tree.fragments.points(i), tree.planes[tree.fragment_plane[i]]);
    if (t && (!best || *t < best->t)) best = RayHit{*t, i};
  }
  return best;
}

// Same answer: both miss, or the same fragment, or hits at the same distance (a tie).
bool same_first_hit(const std::optional<RayHit>& a, const std::optional<RayHit>& b, const Ray& ray, double tie) {
  if (!a || !b) return !a && !b;
  return a->fragment == b->fragment || std::abs(a->t - b->t) * length(ray.dir) <= tie;
}

RayShootCheck check_against_embree(const Tree& tree, int views) {
  ValidationSettings settings;
  settings.views = views;
  return check_ray_shooting(tree, settings);
}

// --- frustum checks

// The centroid, every vertex pulled 1% toward it, and seeded random points of the fan triangles.
std::vector<Vec3> sample_points(const Polygon& poly, Rng& rng) {
  const Vec3 c = centroid(poly);
  std::vector<Vec3> out{c};
  for (const auto& v : poly.verts) out.push_back(lerp(v.p, c, 0.01));
  for (int k = 0; k < 8; ++k) {
    const std::size_t i = 1 + rng.below(poly.verts.size() - 2);
    double a = rng.uniform(), b = rng.uniform();
    if (a + b > 1) a = 1 - a, b = 1 - b;
    out.push_back(poly.verts[0].p + (poly.verts[i].p - poly.verts[0].p) * a + (poly.verts[i + 1].p - poly.verts[0].p) * b);
  }
  return out;
}

struct CullingCheck {
  std::uint64_t missed = 0;         // sample points inside the frustum of fragments not emitted
  std::uint64_t seen_inside = 0;    // sample points inside the frustum of emitted fragments
  std::uint64_t culled = 0;         // fragments not emitted, over the views
};

CullingCheck check_culling(const Tree& tree, std::span<const Frustum> views) {
  CullingCheck out;
  Rng rng(5);
  const double margin = 1e-6 * tree.bounds.diagonal();
  for (const Frustum& f : views) {
    std::vector<bool> emitted(tree.fragments.size(), false);
    for (auto i : culled_visibility_order(tree, f)) emitted[i] = true;
    for (std::uint32_t i = 0; i < tree.fragments.size(); ++i) {
      out.culled += !emitted[i];
      for (const Vec3& p : sample_points(tree.fragments[i].polygon(), rng))
        if (f.contains(p, margin)) (emitted[i] ? out.seen_inside : out.missed) += 1;
    }
  }
  return out;
}

}  // namespace

// ------------------------------------------------------------------------------------------------
// Shape metrics and expected costs on hand-built trees

TEST(ShapeMetrics, HandBuiltTreeGivesPinnedDepthsAndBalance) {
  const TreeMetrics m = measure_tree(four_node_tree());
  EXPECT_EQ(m.nodes, 4u);
  EXPECT_EQ(m.leaves, 2u);
  EXPECT_EQ(m.fragments, 5u);
  EXPECT_EQ(m.max_depth, 3u);
  EXPECT_DOUBLE_EQ(m.mean_depth, 2.5);                // leaves at depths 3 and 2
  EXPECT_DOUBLE_EQ(m.fragment_weighted_depth, 2.0);   // (1*1 + 2*2 + 1*3 + 1*2) / 5
  EXPECT_DOUBLE_EQ(m.mean_balance, 0.75);             // root |3-1|/4, its front child |1-0|/1
}

TEST(ExpectedCosts, OnePlaneHalvingTheBoxCostsOneTestForPointsAndLines) {
  const Tree tree = hand_built({{0, kNull, kNull, 1}});
  const ExpectedCosts c = expected_costs(tree, 0.0);
  EXPECT_DOUBLE_EQ(c.root_volume, 1.0);
  EXPECT_DOUBLE_EQ(c.root_area, 6.0);
  EXPECT_NEAR(c.e_point, 1.0, 1e-12);
  EXPECT_NEAR(c.e_line, 1.0, 1e-12);
}

// Cells: root the unit cube; its front child x > 1/2 (volume 1/2, area 4); that one's front child
// x, y > 1/2 (volume 1/4, area 5/2); the root's back child x < 1/2 (volume 1/2, area 4). Hence
// E_point = 1 + 1/2 + 1/4 + 1/2 and E_line = 1 + (4 + 5/2 + 4) / 6.
TEST(ExpectedCosts, FourNodeTreeGivesSumsOfCellVolumesAndAreas) {
  const ExpectedCosts c = expected_costs(four_node_tree(), 0.0);
  EXPECT_EQ(point_plane_tests(four_node_tree(), {0.75, 0.75, 0.5}), 3u);  // the cell x, y > 1/2
  EXPECT_EQ(point_plane_tests(four_node_tree(), {0.75, 0.25, 0.5}), 2u);  // an empty slot under the front child
  EXPECT_EQ(point_plane_tests(four_node_tree(), {0.25, 0.75, 0.5}), 2u);  // the back child
  EXPECT_NEAR(c.e_point, 2.25, 1e-12);
  EXPECT_NEAR(c.e_line, 2.75, 1e-12);
}

TEST(ExpectedCosts, MarginGrowsTheRootCell) {
  const Tree tree = hand_built({{0, kNull, kNull, 1}});
  const ExpectedCosts c = expected_costs(tree, 0.1);
  const double side = 1 + 2 * 0.1 * std::sqrt(3.0);
  EXPECT_NEAR(c.root_volume, side * side * side, 1e-12);
  EXPECT_NEAR(c.e_point, 1.0, 1e-12);
}

class ExpectedCostsMonteCarlo : public ::testing::TestWithParam<std::tuple<std::string, std::string, Shape>> {};

TEST_P(ExpectedCostsMonteCarlo, ExactCostsAgreeWithPointAndLineSamplingWithinTwoPercent) {
  const auto& [scene, heuristic, shape] = GetParam();
  const Tree tree = build_scene(scene, 300, heuristic, {.shape = shape});
  const double margin = 0.05;
  const ExpectedCosts exact = expected_costs(tree, margin);
  const Box root = root_cell(tree, margin);
  constexpr int kSamples = 100000;
  const double point = monte_carlo_e_point(tree, root, kSamples);
  const double line = monte_carlo_e_line(tree, root, kSamples);
  EXPECT_GT(exact.e_point, 3.0);  // a tree deep enough for the comparison to mean something
  EXPECT_NEAR(point / exact.e_point, 1.0, 0.02) << "exact " << exact.e_point << ", sampled " << point;
  EXPECT_NEAR(line / exact.e_line, 1.0, 0.02) << "exact " << exact.e_line << ", sampled " << line;
}

INSTANTIATE_TEST_SUITE_P(Trees, ExpectedCostsMonteCarlo,
                         ::testing::Values(std::tuple{"random-triangles", "random", Shape::Strict},
                                           std::tuple{"random-triangles", "first", Shape::Coarse},
                                           std::tuple{"cyclic-overlap", "random", Shape::Coarse}));

// ------------------------------------------------------------------------------------------------
// Frustum-culled traversal

TEST(CulledTraversal, VisitsNoMoreNodesThanTheFullOneAndKeepsItsOrder) {
  const Tree tree = build_scene("random-triangles", 400, "random");
  for (const Frustum& f : metric_views(tree.bounds, 8)) {
    TraversalCounters culled_counts, full_counts;
    const auto culled = culled_visibility_order(tree, f, &culled_counts);
    const auto full = visibility_order(tree, f.eye, Order::BackToFront, &full_counts);
    EXPECT_LE(culled_counts.nodes_visited, full_counts.nodes_visited);
    EXPECT_EQ(culled_counts.fragments_emitted, culled.size());
    // A subsequence of the full back-to-front order.
    auto it = full.begin();
    for (auto i : culled) {
      it = std::find(it, full.end(), i);
      ASSERT_NE(it, full.end()) << "fragment " << i << " out of the full order";
    }
  }
}

TEST(CulledTraversal, EmitsEveryFragmentMeetingTheFrustum) {
  for (Shape shape : {Shape::Strict, Shape::Coarse}) {
    const Tree tree = build_scene("random-triangles", 400, "random", {.shape = shape});
    const auto views = metric_views(tree.bounds, 16);
    const CullingCheck c = check_culling(tree, views);
    EXPECT_EQ(c.missed, 0u);
    EXPECT_GT(c.seen_inside, 0u);  // the views do see fragments...
    EXPECT_GT(c.culled, 0u);       // ...and do cull some
  }
}

TEST(CulledTraversal, CorruptedTreeLosesFragmentsInView) {
  Tree tree = build_scene("random-triangles", 400, "random");
  std::swap(tree.nodes[0].front, tree.nodes[0].back);
  EXPECT_GT(check_culling(tree, metric_views(tree.bounds, 16)).missed, 0u);
}

TEST(CulledTraversal, FrustumContainingTheWholeSceneEmitsEverything) {
  const Tree tree = build_scene("cyclic-overlap", 300, "random", {.shape = Shape::Coarse});
  const double d = tree.bounds.diagonal();
  const Frustum f{tree.bounds.center() + Vec3{0.3, -0.2, 1.0} * (2 * d), Vec3{-0.3, 0.2, -1.0}, {0, 1, 0},
                  1.2, 1.2, 0.01 * d, 10 * d};
  for (const FragmentView frag : tree.fragments)
    for (const Vec3& p : frag.p) ASSERT_TRUE(f.contains(p, 0.0));
  auto order = culled_visibility_order(tree, f);
  ASSERT_EQ(order.size(), tree.fragments.size());
  std::sort(order.begin(), order.end());
  for (std::uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
}

// ------------------------------------------------------------------------------------------------
// Ray shooting

TEST(RayShooting, EqualsBruteForceNearestHitOnSeededRays) {
  for (Shape shape : {Shape::Strict, Shape::Coarse}) {
    const Tree tree = build_scene("random-triangles", 300, "random", {.shape = shape});
    const double tie = 1e-9 * tree.bounds.diagonal();
    int hits = 0;
    for (const Ray& ray : metric_rays(tree.bounds, 3000, 7)) {
      const RayShot shot = shoot_ray(tree, ray);
      const auto expected = brute_force_first_hit(tree, ray);
      hits += expected.has_value();
      ASSERT_TRUE(same_first_hit(shot.hit, expected, ray, tie));
      EXPECT_LE(shot.nodes_visited, tree.nodes.size());
    }
    EXPECT_GT(hits, 300);
  }
}

TEST(RayShooting, CorruptedTreeDisagreesWithEmbree) {
  Tree tree = build_scene("random-triangles", 200, "random");
  ASSERT_EQ(check_against_embree(tree, 4).mismatches, 0u);
  std::swap(tree.nodes[0].front, tree.nodes[0].back);
  EXPECT_GT(check_against_embree(tree, 4).mismatches, 0u);
}

// A tiny triangle (1e-4 across) seen from 5e4 away: the Plücker products of the ray aimed at its
// centroid are ~1e-9, far below the rounding of products of vectors 5e4 long.
TEST(RayShooting, AFarEyeHitsATinyFragmentItAimsAt) {
  const double s = 1e-4;
  const Polygon tiny{{{{0.3, 0.2, 0.1}, 0, 0}, {{0.3 + s, 0.2, 0.1}, 0, 0}, {{0.3, 0.2 + s, 0.1}, 0, 0}}, 0};
  const Plane support = *supporting_plane(tiny);
  std::vector<Vec3> corners;
  for (const auto& v : tiny.verts) corners.push_back(v.p);
  const Vec3 eye{2865.96, 41845.2, 30671.9};
  int hits = 0;
  for (double u : {0.2, 0.33, 0.5})
    for (double v : {0.2, 0.33}) {
      const Vec3 target = tiny.verts[0].p + Vec3{u * s, v * s, 0};
      const Ray ray{eye, normalize(target - eye)};
      hits += ray_polygon_hit(ray, corners, support).has_value();
    }
  EXPECT_EQ(hits, 6);
}

// Scenes whose features are a few plane_eps wide put fragments up to plane_eps outside their cells
// and tiny fragments far from the eyes: the walk must still find every first hit.
class RayShootingDegenerate : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(RayShootingDegenerate, FirstHitEqualsTheExactSearchOnEveryRay) {
  const auto& [heuristic, scene] = GetParam();
  const Tree tree = build_scene(scene, 600, heuristic);
  const RayShootCheck c = check_against_embree(tree, 2);
  EXPECT_EQ(c.mismatches, 0u) << "of " << c.rays << " rays; first: "
                              << (c.first_problems.empty() ? "" : c.first_problems.front());
}

INSTANTIATE_TEST_SUITE_P(Scenes, RayShootingDegenerate,
                         ::testing::Combine(::testing::Values("first", "crystal", "naylor", "halving"),
                                            ::testing::Values("near-degenerate", "terrain")),
                         [](const ::testing::TestParamInfo<std::tuple<std::string, std::string>>& info) {
                           std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

using RayCase = std::tuple<std::string, std::string, Shape, bool>;  // heuristic, scene, shape, incremental

class RayShootingEveryHeuristic : public ::testing::TestWithParam<RayCase> {};

TEST_P(RayShootingEveryHeuristic, FirstHitEqualsEmbreeOnTheValidationRays) {
  const auto& [heuristic, scene, shape, incremental] = GetParam();
  const BuildOptions opts{.shape = shape, .incremental = incremental};
  const Tree tree = incremental ? build_incremental_tree(make_scene(scene, {{"n", "200"}, {"seed", "3"}}).polygons, opts)
                                : build_scene(scene, 200, heuristic, opts);
  const RayShootCheck c = check_against_embree(tree, 4);
  EXPECT_GT(c.hits, c.rays / 4);
  EXPECT_EQ(c.mismatches, 0u) << "of " << c.rays << " rays; first: "
                              << (c.first_problems.empty() ? "" : c.first_problems.front());
  // Rays whose two first hits meet where their fragments touch are rare.
  EXPECT_LE(c.ties(), c.rays / 100);
}

// Every heuristic builds recursively; the incremental build consults no heuristic, so it is one case
// per scene and shape, not one per heuristic holding the same tree.
std::vector<RayCase> ray_cases() {
  std::vector<RayCase> out;
  for (const char* scene : {"random-triangles", "cyclic-overlap", "architecture"})
    for (Shape shape : {Shape::Strict, Shape::Coarse}) {
      for (const auto& h : heuristics()) out.emplace_back(h.name, scene, shape, false);
      out.emplace_back(std::string(kIncrementalLabel), scene, shape, true);
    }
  return out;
}

INSTANTIATE_TEST_SUITE_P(
    Registry, RayShootingEveryHeuristic, ::testing::ValuesIn(ray_cases()),
    [](const ::testing::TestParamInfo<RayCase>& info) {
      std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param) + "_" +
                         (std::get<2>(info.param) == Shape::Strict ? "strict" : "coarse") +
                         (std::get<3>(info.param) ? "_incremental" : "_recursive");
      std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
      return name;
    });

// ------------------------------------------------------------------------------------------------
// A chain as deep as the input is long

// The tree `first` builds from n unit squares at z = 0, 1, ..., n-1 facing +z, made directly (the
// build is quadratic on it): node i stores square i on the plane z = i, its front child is node i+1.
Tree chain_tree(std::size_t n) {
  Tree t;
  for (std::size_t i = 0; i < n; ++i) {
    const double z = static_cast<double>(i);
    Node node;
    node.plane = t.planes.add(Plane{{0, 0, 1}, -z});
    node.front = i + 1 < n ? static_cast<std::uint32_t>(i + 1) : kNull;
    node.first = static_cast<std::uint32_t>(i);
    t.nodes.push_back(node);
    const Polygon square{{{{0, 0, z}, 0, 0}, {{1, 0, z}, 1, 0}, {{1, 1, z}, 1, 1}, {{0, 1, z}, 0, 1}},
                         static_cast<std::uint32_t>(i)};
    t.fragments.push_back(square);
    t.fragment_plane.push_back(node.plane);
    for (const auto& v : square.verts) t.bounds.add(v.p);
  }
  t.tol = Tolerance::for_extent(t.bounds.diagonal());
  return t;
}

// Root cell z in [-m, n-1+m]; node k >= 1 is reached by the points above z = k-1, so
// E_point = 1 + sum_{k=1}^{n-1} (n-k+m)/(n-1+2m) = 1 + (n-1)(n/2+m)/(n-1+2m): the chain's worst case.
TEST(DegenerateChain, HundredThousandDeepMetricsRunWithoutRecursionAndPinTheChainsExpectedCost) {
  constexpr std::size_t n = 100000;
  const Tree tree = chain_tree(n);
  const double margin = 0.01, m = margin * tree.bounds.diagonal();
  const ExpectedCosts c = expected_costs(tree, margin);
  const double nd = static_cast<double>(n);
  EXPECT_NEAR(c.e_point / (1 + (nd - 1) * (nd / 2 + m) / (nd - 1 + 2 * m)), 1.0, 1e-9);
  // From above, the walk descends the whole chain before it reaches the top square.
  const RayShot down = shoot_ray(tree, {{0.5, 0.5, nd}, {0, 0, -1}});
  ASSERT_TRUE(down.hit);
  EXPECT_EQ(tree.fragments[down.hit->fragment].source, n - 1);
  EXPECT_EQ(down.nodes_visited, n);
  const Frustum side{{0.5, -2 * nd, nd / 2}, {0, 1, 0}, {0, 0, 1}, 0.5, 0.5, 1.0, 4 * nd};
  EXPECT_EQ(culled_visibility_order(tree, side).size(), n);
}

// ------------------------------------------------------------------------------------------------
// The full metrics

TEST(MeasureTree, FullMetricsAreDeterministicAndOnlyTheyCarryQueryCosts) {
  const Tree tree = build_scene("random-triangles", 300, "random");
  MetricsSettings s;
  s.rays = 500;
  nlohmann::json a = to_json(measure_tree(tree, s)), b = to_json(measure_tree(tree, s));
  a.erase("build_seconds");
  b.erase("build_seconds");
  EXPECT_EQ(a, b);
  EXPECT_GT(a["e_line"].get<double>(), 1.0);
  EXPECT_EQ(a["full_nodes_visited"].get<double>(), static_cast<double>(tree.nodes.size()));
  EXPECT_LT(a["culled_nodes_visited"].get<double>(), a["full_nodes_visited"].get<double>());
  EXPECT_GT(a["ray_nodes_visited"].get<double>(), 0.0);
  EXPECT_FALSE(to_json(measure_tree(tree)).contains("e_point"));
}

// The report's tables take each metric's group, unit and meaning from analysis/metric_docs.json; a
// metric added here without its line there would show up unexplained.
TEST(MeasureTree, EveryEmittedMetricIsDocumentedForTheReport) {
  std::ifstream in(std::string(BSPBENCH_SOURCE_DIR) + "/analysis/metric_docs.json");
  const nlohmann::json file = nlohmann::json::parse(in);
  const nlohmann::json& docs = file["metrics"];
  const auto& groups = file["groups"];
  MetricsSettings s;
  s.rays = 10;
  const nlohmann::json emitted = to_json(measure_tree(build_scene("random-triangles", 100, "random"), s));
  for (const auto& [key, value] : emitted.items()) EXPECT_TRUE(docs.contains(key)) << key << " is not in metric_docs.json";
  for (const auto& [key, doc] : docs.items()) {
    EXPECT_FALSE(doc["meaning"].get<std::string>().empty()) << key;
    EXPECT_NE(std::find(groups.begin(), groups.end(), doc["group"]), groups.end()) << key << ": unknown group";
  }
}

// ------------------------------------------------------------------------------------------------
// Statistics

TEST(Statistics, StudentQuantilesMatchTablesAndApproachTheNormal) {
  EXPECT_NEAR(student_t_975(1), 12.7062, 1e-4);
  EXPECT_NEAR(student_t_975(2), 4.3027, 1e-4);
  EXPECT_NEAR(student_t_975(30), 2.0423, 1e-4);
  EXPECT_NEAR(student_t_975(31), 2.0395, 1e-4);   // first value from the expansion
  EXPECT_NEAR(student_t_975(60), 2.0003, 1e-4);
  EXPECT_NEAR(student_t_975(120), 1.9799, 1e-4);
  EXPECT_NEAR(student_t_975(1000000), 1.95996, 1e-5);
}

TEST(Statistics, SummaryOfAKnownSample) {
  const std::vector<double> xs{1, 2, 3, 4, 5};
  const Summary s = summarize(xs);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.stddev, std::sqrt(2.5), 1e-12);
  EXPECT_NEAR(s.half_width, 2.7764451052 * std::sqrt(2.5) / std::sqrt(5.0), 1e-9);
  const std::vector<double> one{4};
  EXPECT_FALSE(summarize(one).has_interval());
  EXPECT_TRUE(to_json(summarize(one))["ci95"].is_null());
}

TEST(Statistics, PowerLawFitRecoversExponentCoefficientAndR2) {
  const std::vector<double> x{10, 100, 1000, 10000};
  std::vector<double> y;
  for (double v : x) y.push_back(3 * v * v);
  const PowerFit exact = fit_power_law(x, y);
  EXPECT_NEAR(exact.exponent, 2.0, 1e-12);
  EXPECT_NEAR(exact.coefficient, 3.0, 1e-9);
  EXPECT_NEAR(exact.r2, 1.0, 1e-12);
  y[1] *= 3;
  EXPECT_LT(fit_power_law(x, y).r2, 0.999);
  EXPECT_THROW(fit_power_law(std::vector<double>{1, 1}, std::vector<double>{2, 3}), std::invalid_argument);
}

// log x = 0, 1, 2, 3 and log y = 0, 1.1, 1.9, 3.0: slope 4.9 / 5 = 0.98, residuals 0.03, 0.09, -0.09,
// 0.03 (SSE 0.018, Syy 4.82), se = sqrt(0.018 / 2 / 5), t(0.975, 2) = 4.302653: half-width 0.182546.
TEST(Statistics, PowerLawFitIntervalMatchesAHandComputedOne) {
  std::vector<double> x, y;
  for (double ly : {0.0, 1.1, 1.9, 3.0}) {
    x.push_back(std::exp(static_cast<double>(x.size())));
    y.push_back(std::exp(ly));
  }
  const PowerFit f = fit_power_law(x, y);
  EXPECT_NEAR(f.exponent, 0.98, 1e-12);
  EXPECT_NEAR(f.half_width, 0.182546, 1e-6);
  EXPECT_NEAR(f.r2, 1 - 0.018 / 4.82, 1e-12);
  EXPECT_TRUE(f.has_interval());
  const PowerFit two = fit_power_law(std::vector<double>{1, 10}, std::vector<double>{2, 20});
  EXPECT_FALSE(two.has_interval());  // no degree of freedom left
  EXPECT_EQ(two.half_width, 0.0);
}

TEST(Statistics, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median(std::vector<double>{5, 1, 3}), 3.0);
  EXPECT_EQ(median(std::vector<double>{4, 1, 3, 2}), 2.5);
  EXPECT_EQ(median(std::vector<double>{}), 0.0);
}

// Exact p-values by counting the C(m+n, m) equally likely rank arrangements under the null.
TEST(Statistics, MannWhitneyExactPValuesOfSmallSamples) {
  using V = std::vector<double>;
  // Complete separation of 3 and 3: 1 arrangement of 20 in each tail.
  MannWhitney r = mann_whitney_u(V{1, 2, 3}, V{4, 5, 6});
  EXPECT_EQ(r.u, 0.0);
  EXPECT_NEAR(r.p, 2.0 / 20, 1e-15);
  EXPECT_NEAR(mann_whitney_u(V{4, 5, 6}, V{1, 2, 3}).p, 2.0 / 20, 1e-15);
  EXPECT_EQ(mann_whitney_u(V{4, 5, 6}, V{1, 2, 3}).u, 9.0);
  // 4 and 4: 2 of 70 arrangements are at least as extreme.
  EXPECT_NEAR(mann_whitney_u(V{1, 2, 3, 4}, V{5, 6, 7, 8}).p, 2.0 / 70, 1e-15);
  // Interleaved 1 3 5 | 2 4 6: U = 3; U counts 1, 1, 2, 3 for u = 0..3, so P(U <= 3) = 7/20.
  r = mann_whitney_u(V{1, 3, 5}, V{2, 4, 6});
  EXPECT_EQ(r.u, 3.0);
  EXPECT_NEAR(r.p, 0.7, 1e-15);
}

// Normal approximation: z = (|U - mn/2| - 1/2) / sigma, sigma^2 = mn/12 ((N+1) - sum(t^3-t)/(N(N-1))).
TEST(Statistics, MannWhitneyNormalApproximationWithTieCorrection) {
  using V = std::vector<double>;
  V low, high;
  for (int i = 1; i <= 10; ++i) {
    low.push_back(i);
    high.push_back(i + 10);
  }
  // U = 0, sigma^2 = 100 * 21 / 12 = 175: z = 49.5 / sqrt(175) = 3.7418, p = erfc(z / sqrt 2).
  EXPECT_NEAR(mann_whitney_u(low, high).p, 1.826717911e-4, 1e-12);
  // 1 1 2 2 | 2 3 3 3: ranks 1.5 1.5 4 4 | 4 7 7 7, U = 11 - 10 = 1; ties 2, 3, 3 give
  // sum(t^3 - t) = 54, sigma^2 = 16/12 (9 - 54/56), z = 6.5 / sigma, p = 0.0470574...
  const MannWhitney r = mann_whitney_u(V{1, 1, 2, 2}, V{2, 3, 3, 3});
  EXPECT_EQ(r.u, 1.0);
  EXPECT_NEAR(r.p, 0.04705744628, 1e-10);
  // Every value tied, or an empty sample: no evidence either way.
  EXPECT_EQ(mann_whitney_u(V{2, 2, 2}, V{2, 2, 2, 2, 2, 2, 2, 2}).p, 1.0);
  EXPECT_EQ(mann_whitney_u(V{}, V{1, 2}).p, 1.0);
}

// ------------------------------------------------------------------------------------------------
// bspbench compare

namespace {

struct Output {
  int code;
  std::string out;
};

Output run_cli(const std::string& args) {
  const std::string cmd = std::string(BSPBENCH_EXE) + " " + args + " 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

}  // namespace

TEST(CompareCommand, ReportsMeanAndIntervalPerHeuristicWithValidation) {
  const Output r = run_cli("compare --scene random-triangles --n 80 --heuristics first,random --seeds 3 "
                           "--views 2 --rays 50 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["seeds"], nlohmann::json({1, 2, 3}));
  ASSERT_EQ(j["heuristics"].size(), 2u);
  for (const auto& h : j["heuristics"]) {
    const auto& e = h["metrics"]["e_point"];
    EXPECT_EQ(e["n"], 3);
    EXPECT_LE(e["ci95"][0].get<double>(), e["mean"].get<double>());
    EXPECT_GE(e["ci95"][1].get<double>(), e["mean"].get<double>());
    EXPECT_EQ(h["validation"]["failures"], 0);
    EXPECT_GT(h["validation"]["order_rays"].get<int>(), 0);
    EXPECT_GT(h["validation"]["ray_shoot_rays"].get<int>(), 0);
    EXPECT_EQ(h["runs"].size(), 3u);
  }
}

// The incremental build consults no heuristic: one entry labelled "incremental", not one per
// heuristic holding the same tree.
TEST(CompareCommand, IncrementalBuildIsOneEntryAndRefusesHeuristics) {
  const Output r = run_cli("compare --scene random-triangles --n 60 --incremental --order shuffled --seeds 2 "
                           "--views 1 --rays 20 --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["build"], "incremental");
  ASSERT_EQ(j["heuristics"].size(), 1u);
  EXPECT_EQ(j["heuristics"][0]["heuristic"], "incremental");
  EXPECT_EQ(run_cli("compare --scene random-triangles --n 60 --incremental --heuristics all").code, 2);
}

TEST(CompareCommand, BadArgumentsExitWithTwo) {
  EXPECT_EQ(run_cli("compare --scene random-triangles --heuristics nosuch").code, 2);
  EXPECT_EQ(run_cli("compare --scene random-triangles --heuristics all --seeds 0").code, 2);
  EXPECT_EQ(run_cli("compare --scene random-triangles --heuristics all --cell-margin -1").code, 2);
}
