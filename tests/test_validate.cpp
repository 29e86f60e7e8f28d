// Visibility orders checked against Embree: the Embree all-hits caster itself, the deterministic
// eyes, BSP orders of every heuristic, shape and build mode passing, wrong orders (reversed, centroid
// depth sort) caught, and the files written by `bspbench order` holding a valid order.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "catalog.h"
#include "common/errors.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

using namespace bsp;

namespace {

Polygon square(double z, double x0, std::uint32_t source) {
  return {{{{x0, 0, z}, 0, 0}, {{x0 + 1, 0, z}, 1, 0}, {{x0 + 1, 1, z}, 1, 1}, {{x0, 1, z}, 0, 1}}, source};
}

Tree build(const Scene& scene, std::string_view heuristic, BuildOptions opts = {}) {
  auto splitter = make_splitter(heuristic, {}, 1);
  return build_tree(scene.polygons, *splitter, opts);
}

// Small grids keep the tests fast; the fragment sample rays still probe every fragment.
ValidationSettings quick(int views) {
  ValidationSettings s;
  s.views = views;
  s.grid = 24;
  s.cube_grid = 10;
  return s;
}

std::string first_problem(const ValidationReport& r) {
  return r.first_problems.empty() ? std::string("none") : r.first_problems.front();
}

// Input polygons sorted by the distance of their centroid from the eye, farthest first: the
// painter's algorithm without splitting, which cyclic overlaps defeat.
std::vector<std::uint32_t> centroid_sort(const std::vector<Polygon>& polys, const Vec3& eye) {
  std::vector<std::uint32_t> order(polys.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return length(centroid(polys[a]) - eye) > length(centroid(polys[b]) - eye);
  });
  return order;
}

}  // namespace

TEST(EmbreeScene, AllHitsSeeThroughEverythingSortedAndOncePerFragment) {
  // Two unit squares stacked at z = 0 and z = 1 (fan-triangulated along a diagonal), a third one
  // beside the first sharing its edge x = 1.
  const std::vector<Polygon> polys = {square(1, 0, 0), square(0, 0, 1), square(0, 1, 2)};
  const EmbreeScene scene(polys);
  // Straight up through the diagonal x = y, where both fan triangles of each square meet.
  const Ray up{{0.5, 0.5, -1}, {0, 0, 2}};
  const auto hits = scene.all_hits(up);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(hits[0].fragment, 1u);
  EXPECT_DOUBLE_EQ(hits[0].t, 0.5);
  EXPECT_EQ(hits[1].fragment, 0u);
  EXPECT_DOUBLE_EQ(hits[1].t, 1.0);
  const auto first = scene.first_hit(up);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->fragment, 1u);
  // Through the edge x = 1 shared by squares 1 and 2 (a tie at t = 1), then the edge of square 0.
  const auto edge = scene.all_hits({{1.0, 0.3, -1}, {0, 0, 1}});
  ASSERT_EQ(edge.size(), 3u);
  EXPECT_EQ(scene.tie_reason({{1.0, 0.3, -1}, {0, 0, 1}}, edge[0], edge[1]), TieReason::Edge);
  EXPECT_EQ(edge[0].fragment + edge[1].fragment, 3u);
  EXPECT_EQ(edge[2].fragment, 0u);
  EXPECT_FALSE(scene.first_hit({{5, 5, -1}, {0, 0, 1}}).has_value());
}

TEST(EmbreeScene, BatchedHitsAreTheHitsOfEachRayCastAlone) {
  // Packets mix rays that meet many fragments, few and none (some miss the box): each ray must get
  // exactly its own hits whatever its lane.
  const Scene scene = make_scene("random-triangles", {{"n", "300"}, {"seed", "2"}});
  const Tree tree = build(scene, "first");
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  const EmbreeScene embree(fragments);
  std::vector<Ray> rays = validation_rays(fragments, tree.bounds, validation_eyes(tree.bounds, 1)[0], quick(1));
  for (std::size_t i = 0; i < rays.size(); i += 7) rays[i].dir = -rays[i].dir;
  HitBatch batch;
  embree.all_hits(rays, batch);
  std::size_t total = 0;
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const std::vector<Hit> alone = embree.all_hits(rays[r]);
    const std::span<const Hit> batched = batch.of(r);
    ASSERT_EQ(batched.size(), alone.size()) << "ray " << r;
    for (std::size_t k = 0; k < alone.size(); ++k) {
      EXPECT_EQ(batched[k].fragment, alone[k].fragment) << "ray " << r;
      EXPECT_EQ(batched[k].t, alone[k].t) << "ray " << r;
    }
    total += alone.size();
  }
  EXPECT_GT(total, rays.size());
}

TEST(EmbreeScene, AGrazingNearMissAtASharedEdgeIsNotAHit) {
  // b: the unit square on z = 0. a: a strip rising at 60 degrees from b's edge x = 1. The eye sits
  // 1e-5 off a's plane, below z = 0, so rays to b's points just short of the edge run almost inside
  // a's plane: Embree's float triangles of a are within rounding of those rays, but in exact
  // arithmetic the rays cross a's plane outside a. Taking Embree's candidate at that crossing would
  // put a in front of b on the ray (the failure this test guards against: a "hit" far from a).
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
  const Polygon b = square(0, 0, 0);
  const Polygon a{{{{1, 0, 0}, 0, 0}, {{1 + 0.5 * c, 0, 0.5 * s}, 0, 0}, {{1 + 0.5 * c, 1, 0.5 * s}, 0, 0},
                   {{1, 1, 0}, 0, 0}},
                  1};
  const Vec3 n_a{-s, 0, c};
  const Vec3 eye = Vec3{1 - 2 * c, 0.5, -2 * s} - n_a * 1e-5;
  const std::vector<Polygon> polys = {b, a};
  const EmbreeScene scene(polys);
  std::vector<Ray> rays;
  for (double delta : {1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4})
    for (double y : {0.2, 0.5, 0.8}) {
      const Ray ray{eye, Vec3{1 - delta, y, 0} - eye};
      const auto hits = scene.all_hits(ray);
      ASSERT_EQ(hits.size(), 1u) << "delta " << delta << " y " << y;
      EXPECT_EQ(hits[0].fragment, 0u);
      rays.push_back(ray);
    }
  // A BSP on b's plane draws a (in front of it, the far side from this eye) first.
  const std::vector<std::uint32_t> a_then_b = {1, 0};
  EXPECT_EQ(check_order(scene, rays, a_then_b).violations, 0u);
}

// a: the unit square on z = 0. A ray descends toward a with slope c and crosses z = 0 just inside
// a's edge x = 1 (closer to it than a hit radius). b: a vertical square standing on nothing, its
// foot halfway between a's plane and the ray, which crosses b `gap` before a. Drawing b before a
// contradicts the ray.
OrderCheck separated_pair(double c, double gap) {
  const double delta = -0.5e-9;  // plane_eps is 1.4e-9 for this box
  const double t_a = 2 + delta;
  const Vec3 origin{-1, 0.5, c * t_a}, dir{1, 0, -c};
  const double x = -1 + t_a - gap, z = origin.z - c * (t_a - gap);
  const Polygon a = square(0, 0, 0);
  const Polygon b{{{{x, 0, z / 2}, 0, 0}, {{x, 1, z / 2}, 0, 0}, {{x, 1, 0.1}, 0, 0}, {{x, 0, 0.1}, 0, 0}}, 1};
  const std::vector<Polygon> polys = {a, b};
  const EmbreeScene scene(polys);
  const std::vector<Ray> rays = {{origin, dir}};
  EXPECT_EQ(scene.all_hits(rays[0]).size(), 2u);
  const std::vector<std::uint32_t> b_then_a = {1, 0};
  return check_order(scene, rays, b_then_a);
}

// Where the ray meets b more than 2 plane_eps above a's plane, the pair is judged, however flat the
// ray and however close the hits along it (1e-7 is 70 plane_eps).
TEST(EmbreeScene, HitsMoreThanTwoToleranceApartAreJudgedHoweverFlatTheRay) {
  for (double gap : {1e-4, 1e-6, 1e-7}) EXPECT_EQ(separated_pair(0.5, gap).violations, 1u) << gap;
  for (double gap : {1e-4, 1e-5}) EXPECT_EQ(separated_pair(6e-4, gap).violations, 1u) << gap;
}

// A flat ray meets b 6e-10 above a's plane (0.4 plane_eps), just above b's foot, which rests on a
// within the tolerance: the ray meets them where they touch, an edge tie.
TEST(EmbreeScene, AFlatRayThroughAFootRestingWithinTheToleranceIsAnEdgeTie) {
  const OrderCheck c = separated_pair(6e-4, 1e-6);
  EXPECT_EQ(c.violations, 0u);
  EXPECT_EQ(c.ties_edge, 1u);
}

// a: the floor square z = 0. b: a wall standing on it along the line x = 0.5 (its bottom edge
// rests on a's face, inside a). A ray meeting both where they touch is an edge tie in either
// order, even when it grazes the floor; one meeting the wall high above the floor is judged.
TEST(EmbreeScene, AWallStandingOnAFloorTiesOnlyWhereTheyTouch) {
  const Polygon a = square(0, 0, 0);
  const Polygon b{{{{0.5, 0.2, 0}, 0, 0}, {{0.5, 0.8, 0}, 0, 0}, {{0.5, 0.8, 1}, 0, 0}, {{0.5, 0.2, 1}, 0, 0}}, 1};
  const std::vector<Polygon> polys = {a, b};
  const EmbreeScene scene(polys);
  for (double slope : {1.0, 1e-2, 1e-4}) {
    const Ray at_foot{{0.5 - 1 / slope, 0.5, 1}, {1, 0, -slope}};
    const auto hits = scene.all_hits(at_foot);
    ASSERT_EQ(hits.size(), 2u) << slope;
    EXPECT_EQ(scene.tie_reason(at_foot, hits[0], hits[1]), TieReason::Edge) << slope;
  }
  const Ray high{{-1, 0.5, 0.5}, {1, 0, -0.1}};  // meets the wall at z = 0.35, the floor at x = 4: past a
  const Ray steep{{0.25, 0.5, 0.6}, {1, 0, -1}};  // the wall at z = 0.35, then the floor at x = 0.85
  const auto hits = scene.all_hits(steep);
  ASSERT_EQ(hits.size(), 2u);
  EXPECT_EQ(scene.tie_reason(steep, hits[0], hits[1]), TieReason::None);
  EXPECT_EQ(scene.all_hits(high).size(), 1u);
  const std::vector<Ray> rays = {steep};
  const std::vector<std::uint32_t> wall_first = {1, 0}, floor_first = {0, 1};
  EXPECT_EQ(check_order(scene, rays, floor_first).violations, 0u);
  EXPECT_EQ(check_order(scene, rays, wall_first).violations, 1u);
}

// Two overlapping squares on one plane: every ray through both is a coplanar tie, in either order.
TEST(EmbreeScene, OverlappingCoplanarFragmentsTie) {
  const std::vector<Polygon> polys = {square(0, 0, 0), square(0, 0.5, 1)};
  const EmbreeScene scene(polys);
  const std::vector<Ray> rays = {{{0.75, 0.5, 1}, {0.1, 0.2, -1}}, {{0.7, 0.3, -1}, {0, 0, 1}}};
  for (const auto& order : {std::vector<std::uint32_t>{0, 1}, std::vector<std::uint32_t>{1, 0}}) {
    const OrderCheck c = check_order(scene, rays, order);
    EXPECT_EQ(c.violations, 0u);
    EXPECT_EQ(c.ties_coplanar, 2u);
    EXPECT_EQ(c.pairs_checked, 0u);
  }
}

// a: the unit square on z = 1; b: a square on z = 0 under a's edge x = 1. A ray from above passes
// a's edge outside a by half a plane_eps (a boundary tie for ray shooting: whether it meets a is
// open) and meets b. Where b lies far inside under that edge, a ray turned by a hair meets both, so
// drawing a before b is judged and caught; where b ends right under the edge, the pair ties.
TEST(EmbreeScene, ANearMissOverAFragmentThatSurelyOverlapsIsJudged) {
  for (const double b_x0 : {0.5, 1.0 - 1e-12}) {
    const std::vector<Polygon> polys = {square(1, 0, 0), square(0, b_x0, 1)};
    const EmbreeScene scene(polys);
    const double eps = scene.plane_eps();
    const Ray ray{{1 + 0.5 * eps, 0.5, 3}, {0, 0, -1}};
    const auto hits = scene.all_hits(ray);
    ASSERT_EQ(hits.size(), 2u) << b_x0;
    EXPECT_LT(hits[0].inside, 0.0);
    EXPECT_EQ(scene.tie_reason(ray, hits[0], hits[1]), TieReason::Boundary);
    const bool deep = b_x0 == 0.5;
    EXPECT_EQ(scene.overlap_nearby(hits[0], hits[1]), deep) << b_x0;
    const std::vector<Ray> rays = {ray};
    const std::vector<std::uint32_t> near_first = {0, 1}, far_first = {1, 0};
    EXPECT_EQ(check_order(scene, rays, far_first).violations, 0u);
    const OrderCheck wrong = check_order(scene, rays, near_first);
    EXPECT_EQ(wrong.violations, deep ? 1u : 0u) << b_x0;
    EXPECT_EQ(wrong.ties_boundary, deep ? 0u : 1u) << b_x0;
  }
}

TEST(EmbreeScene, CheckOrderRejectsAnOrderThatIsNotAPermutation) {
  const std::vector<Polygon> polys = {square(1, 0, 0), square(0, 0, 1)};
  const EmbreeScene scene(polys);
  const std::vector<Ray> rays = {{{0.5, 0.5, -1}, {0, 0, 1}}};
  const std::vector<std::uint32_t> repeated = {0, 0}, short_order = {0}, out_of_range = {0, 2};
  EXPECT_THROW(check_order(scene, rays, repeated), InputError);
  EXPECT_THROW(check_order(scene, rays, short_order), InputError);
  EXPECT_THROW(check_order(scene, rays, out_of_range), InputError);
  // From below, square 1 (z = 0) is nearer: it must be drawn last.
  const std::vector<std::uint32_t> right = {0, 1}, wrong = {1, 0};
  EXPECT_EQ(check_order(scene, rays, right).violations, 0u);
  const OrderCheck bad = check_order(scene, rays, wrong);
  EXPECT_EQ(bad.violations, 1u);
  ASSERT_EQ(bad.examples.size(), 1u);
  EXPECT_EQ(bad.examples[0], std::make_pair(1u, 0u));
}

TEST(ValidationEyes, AreDeterministicAndAlternateOutsideAndInsideTheBox) {
  const Box box{{0, 0, 0}, {2, 1, 3}};
  const auto eyes = validation_eyes(box, 7);
  ASSERT_EQ(eyes.size(), 7u);
  EXPECT_EQ(eyes, validation_eyes(box, 7));
  for (std::size_t k = 0; k < eyes.size(); ++k) EXPECT_EQ(box.contains(eyes[k]), k % 2 == 1) << "eye " << k;
  // A flat box still gets inside eyes off its plane.
  const auto flat = validation_eyes(Box{{0, 0, 0}, {1, 1, 0}}, 2);
  EXPECT_NE(flat[1].z, 0.0);
}

class FoundationOrders : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(FoundationOrders, HaveNoViolationsFromAnyView) {
  const auto& [heuristic, scene_name] = GetParam();
  const Scene scene = make_scene(scene_name, {{"n", "300"}, {"seed", "3"}});
  const Tree tree = build(scene, heuristic);
  const ValidationReport r = validate_tree(tree, quick(6));
  EXPECT_EQ(r.views, 6);
  EXPECT_GT(r.pairs_checked, 0u);
  EXPECT_EQ(r.violations, 0u) << first_problem(r);
}

INSTANTIATE_TEST_SUITE_P(Scenes, FoundationOrders,
                         ::testing::Combine(::testing::Values("first", "random"),
                                            ::testing::Values("random-triangles", "cyclic-overlap")));

TEST(WrongOrders, ReversedBspOrderIsCaught) {
  const Scene scene = make_scene("cyclic-overlap", {{"n", "300"}, {"seed", "3"}});
  const Tree tree = build(scene, "random");
  for (const Vec3& eye : validation_eyes(tree.bounds, 2)) {
    auto order = visibility_order(tree, eye, Order::BackToFront);
    ASSERT_EQ(validate_order(tree.fragments.to_polygons(), eye, order, quick(1)).violations, 0u);
    std::reverse(order.begin(), order.end());
    EXPECT_GT(validate_order(tree.fragments.to_polygons(), eye, order, quick(1)).violations, 0u);
  }
}

TEST(WrongOrders, CentroidDepthSortOfCyclicOverlapsIsCaught) {
  const Scene scene = make_scene("cyclic-overlap", {{"n", "300"}, {"seed", "3"}});
  const Box box = bounds(scene);
  for (const Vec3& eye : validation_eyes(box, 2)) {
    const ValidationReport r = validate_order(scene.polygons, eye, centroid_sort(scene.polygons, eye), quick(1));
    EXPECT_GT(r.violations, 0u);
  }
}

TEST(WrongOrders, CountsAreTheSameOnOneAndTwoThreadsAndInAnyRayOrder) {
  const Scene scene = make_scene("random-triangles", {{"n", "300"}, {"seed", "5"}});
  const Tree tree = build(scene, "first");
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  const EmbreeScene embree(fragments);
  const Vec3 eye = validation_eyes(tree.bounds, 1)[0];
  auto order = visibility_order(tree, eye, Order::BackToFront);
  std::reverse(order.begin(), order.end());
  const auto rays = validation_rays(fragments, tree.bounds, eye, quick(1));
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const OrderCheck one = check_order(embree, rays, order);
  const std::vector<Ray> reversed(rays.rbegin(), rays.rend());
  const OrderCheck backwards = check_order(embree, reversed, order);
  omp_set_num_threads(2);
  const OrderCheck two = check_order(embree, rays, order);
  omp_set_num_threads(threads);
  EXPECT_GT(one.violations, 0u);
  for (const OrderCheck& other : {two, backwards}) {
    EXPECT_EQ(one.hits, other.hits);
    EXPECT_EQ(one.pairs_checked, other.pairs_checked);
    EXPECT_EQ(one.violations, other.violations);
    EXPECT_EQ(one.hit_pairs, other.hit_pairs);
    EXPECT_EQ(one.ties_coplanar, other.ties_coplanar);
    EXPECT_EQ(one.ties_edge, other.ties_edge);
    EXPECT_EQ(one.examples, other.examples);
  }
}

// --- every registered heuristic, shape and build mode

enum class Mode { Recursive, IncrementalGiven, IncrementalShuffled };

class EveryHeuristic : public ::testing::TestWithParam<std::tuple<std::string, Shape, Mode>> {};

// An incremental build consults no heuristic, so it is built once per case, not once per heuristic.
TEST_P(EveryHeuristic, TreesPassInvariantsAndTheirOrdersHaveNoViolations) {
  const auto& [scene_name, shape, mode] = GetParam();
  const Scene scene = make_scene(scene_name, {{"n", "120"}, {"seed", "4"}});
  BuildOptions opts{.shape = shape,
                    .incremental = mode != Mode::Recursive,
                    .order = mode == Mode::IncrementalShuffled ? InsertOrder::Shuffled : InsertOrder::Given,
                    .order_seed = 7};
  std::vector<std::string> labels;
  if (opts.incremental) labels.emplace_back(kIncrementalLabel);
  else
    for (const HeuristicInfo& h : heuristics()) labels.push_back(h.name);
  for (const std::string& label : labels) {
    SCOPED_TRACE("heuristic " + label);
    const Tree tree = opts.incremental ? build_incremental_tree(scene.polygons, opts) : build(scene, label, opts);
    const InvariantReport inv = check_tree_invariants(tree, scene.polygons);
    EXPECT_TRUE(inv.ok()) << (inv.first_problems.empty() ? "" : inv.first_problems.front());
    const ValidationReport r = validate_tree(tree, quick(4));
    EXPECT_EQ(r.violations, 0u) << first_problem(r);
  }
}

std::string registry_case_name(const ::testing::TestParamInfo<EveryHeuristic::ParamType>& info) {
  static const char* const kModes[] = {"recursive", "incremental_given", "incremental_shuffled"};
  std::string scene = std::get<0>(info.param);
  std::replace(scene.begin(), scene.end(), '-', '_');
  return scene + (std::get<1>(info.param) == Shape::Strict ? "_strict_" : "_coarse_") +
         kModes[static_cast<int>(std::get<2>(info.param))];
}

INSTANTIATE_TEST_SUITE_P(
    Registry, EveryHeuristic,
    ::testing::Combine(::testing::Values("random-triangles", "cyclic-overlap", "coplanar-heavy"),
                       ::testing::Values(Shape::Strict, Shape::Coarse),
                       ::testing::Values(Mode::Recursive, Mode::IncrementalGiven, Mode::IncrementalShuffled)),
    registry_case_name);

// --- the files of `bspbench order`, checked independently

namespace {

// Polygons of an OBJ written by `bspbench order`: face k becomes polygon k.
std::vector<Polygon> read_obj_faces(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<Vec3> points;
  std::vector<Polygon> faces;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      Vec3 p;
      s >> p.x >> p.y >> p.z;
      points.push_back(p);
    } else if (tag == "f") {
      Polygon poly;
      poly.source = static_cast<std::uint32_t>(faces.size());
      for (std::size_t index; s >> index;) poly.verts.push_back({points.at(index - 1), 0, 0});
      faces.push_back(std::move(poly));
    }
  }
  return faces;
}

std::filesystem::path fresh_temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("bspbench_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

TEST(OrderCommand, WritesEveryFragmentOnceInAnOrderEmbreeAccepts) {
  const auto dir = fresh_temp_dir("order");
  const Vec3 eye{2.31, -1.73, 3.07};
  const std::string cmd = std::string(BSPBENCH_EXE) +
                          " order --scene cyclic-overlap --n 150 --seed 2 --heuristic random --eye 2.31,-1.73,3.07 --out " +
                          (dir / "run").string() + " > " + (dir / "stdout").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::vector<Polygon> faces = read_obj_faces(dir / "run.obj");
  std::ifstream order_file(dir / "run.order.json");
  const nlohmann::json j = nlohmann::json::parse(order_file);
  EXPECT_EQ(j["eye"].get<std::vector<double>>(), (std::vector<double>{eye.x, eye.y, eye.z}));
  const auto order = j["back_to_front"].get<std::vector<std::uint32_t>>();
  ASSERT_EQ(order.size(), faces.size());
  ASSERT_GE(faces.size(), 150u);
  auto sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i) << "fragment missing or repeated";
  const ValidationReport r = validate_order(faces, eye, order, quick(1));
  EXPECT_GT(r.pairs_checked, 0u);
  EXPECT_EQ(r.violations, 0u) << first_problem(r);
  std::filesystem::remove_all(dir);
}
