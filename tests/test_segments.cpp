// 2D trees: segments split in homogeneous coordinates, every registered heuristic building valid
// 2D trees in every shape (one implementation with 3D), the leafy shape's facing and group rules,
// the checks that must catch a broken 2D tree, and the random autopartition bound.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "catalog.h"
#include "geometry/segment2.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

using namespace bsp;

namespace {

Polygon seg(double ax, double ay, double bx, double by, std::uint32_t source) {
  return Polygon{{Vertex{{ax, ay, 0}}, Vertex{{bx, by, 0}}}, source};
}

Tree build(const std::vector<Polygon>& segs, std::string_view heuristic, Shape shape,
           std::vector<std::uint32_t> groups = {}) {
  auto splitter = make_splitter(heuristic, {}, 1);
  BuildOptions options;
  options.shape = shape;
  options.leaf_groups = std::move(groups);
  return build_tree(segs, *splitter, options);
}

// The inward-facing walls of an axis-aligned room [x0, x1] x [y0, y1]: a segment's front is on its
// right, so the walls run clockwise, as a Doom room's one-sided linedefs do.
std::vector<Polygon> room(double x0, double y0, double x1, double y1, std::uint32_t first) {
  return {seg(x0, y0, x0, y1, first), seg(x0, y1, x1, y1, first + 1), seg(x1, y1, x1, y0, first + 2),
          seg(x1, y0, x0, y0, first + 3)};
}

}  // namespace

TEST(SegmentSplit, CutPointLiesOnBothLinesAndPartsKeepTheDirection) {
  const Polygon s = seg(0, 0, 3, 1, 7);
  const Plane l = *line_through({1, -5, 0}, {2, 5, 0});
  Polygon front, back;
  const SplitKept kept = split_segment_into(s, l, 1e-12, front, back);
  ASSERT_TRUE(kept.front && kept.back);
  const Vec3 x = front.verts[1].p.x == back.verts[0].p.x ? front.verts[1].p : front.verts[0].p;
  EXPECT_NEAR(l.distance(x), 0.0, 1e-12);
  EXPECT_NEAR(line_through(s.verts[0].p, s.verts[1].p)->distance(x), 0.0, 1e-12);
  for (const Polygon* part : {&front, &back}) {
    EXPECT_EQ(part->source, 7u);
    const Vec3 d = part->verts[1].p - part->verts[0].p;
    EXPECT_GT(d.x * 3 + d.y * 1, 0) << "a part runs against the segment";
  }
  EXPECT_GT(l.distance(front.verts[0].p) + l.distance(front.verts[1].p), 0);
  EXPECT_NEAR(measure(front) + measure(back), measure(s), 1e-12);
}

// a × b in world coordinates loses the line of a short segment far from the origin (its terms are
// 10^8 here, their rounding 10^-8, the segment 3·10^-7 long): the cut must stay on the segment.
TEST(SegmentSplit, ShortSegmentFarFromTheOriginIsCutOnItsLine) {
  const Vec3 a{1e4 + 0.1234, 1e4 - 0.5678, 0}, b = a + Vec3{3e-7, 1e-7, 0};
  const Plane cut = *line_through(a + Vec3{1.5e-7, -1, 0}, a + Vec3{1.5e-7, 1, 0});
  const Vec3 x = intersect(cut, a, b);
  EXPECT_NEAR(line_through(a, b)->distance(x), 0.0, 1e-12);
  EXPECT_NEAR(cut.distance(x), 0.0, 1e-12);
  EXPECT_NEAR(x.x, a.x + 1.5e-7, 1e-11);
}

TEST(SegmentSplit, FrontIsTheRightOfTheDirection) {
  const Plane l = *line_through({0, 0, 0}, {1, 0, 0});
  EXPECT_LT(l.distance({0, 1, 0}), 0);
  EXPECT_GT(l.distance({0, -1, 0}), 0);
}

// One implementation per heuristic: every registered heuristic builds 2D trees that pass the
// invariants and the Embree order check, in every shape.
TEST(SegmentTrees, EveryHeuristicAndShapeBuildsValidOrders) {
  const Scene scene = make_scene("random-segments", {{"n", "300"}, {"seed", "3"}});
  for (const auto& h : heuristics())
    for (Shape shape : {Shape::Strict, Shape::Coarse, Shape::Leafy}) {
      SCOPED_TRACE(h.name + std::string(" ") + shape_name(shape));
      const Tree tree = build(scene.polygons, h.name, shape);
      const InvariantReport inv = check_tree_invariants(tree, scene.polygons);
      EXPECT_TRUE(inv.ok()) << (inv.first_problems.empty() ? "" : inv.first_problems[0]);
      const std::vector<Vec3> eyes = {{0.5, 0.5, 0}, {0.1, 0.9, 0}, {-0.5, 0.3, 0}};
      const ValidationReport order = validate_segment_tree(tree, eyes);
      EXPECT_EQ(order.violations, 0u);
      EXPECT_GT(order.pairs_checked, 100u) << "the check compared too little to mean anything";
    }
}

TEST(SegmentTrees, OrderCheckCatchesSwappedChildren) {
  const Scene scene = make_scene("random-segments", {{"n", "300"}, {"seed", "3"}});
  Tree tree = build(scene.polygons, "crystal", Shape::Strict);
  std::uint64_t caught = 0;
  for (std::uint32_t i = 0; i < 8 && i < tree.nodes.size(); ++i) {
    Tree broken = tree;
    std::swap(broken.nodes[i].front, broken.nodes[i].back);
    caught += validate_segment_tree(broken, std::vector<Vec3>{{0.5, 0.5, 0}, {0.2, 0.7, 0}}).violations > 0;
  }
  EXPECT_GE(caught, 6u) << "swapping a node's children near the root should break the order";
}

// Two rooms side by side share the wall x = 1 as a two-sided line: its two sides face opposite ways.
TEST(LeafyTrees, OppositeFacesOfOneLineEndInDifferentLeaves) {
  std::vector<Polygon> segs = room(0, 0, 1, 1, 0);
  for (Polygon& p : room(1, 0, 2, 1, 4)) segs.push_back(p);
  const Tree tree = build(segs, "first", Shape::Leafy);
  ASSERT_TRUE(check_tree_invariants(tree, segs).ok());
  EXPECT_EQ(tree.stats.n_input, 8u);
  EXPECT_GE(tree.nodes.size(), 3u) << "two rooms cannot share a leaf";
  for (std::uint32_t n = 0; n < tree.nodes.size(); ++n) {
    const FragmentRange r = tree.fragments_of(n);
    if (!tree.nodes[n].is_cell_leaf()) {
      EXPECT_EQ(r.size(), 0u) << "an inner node of a leafy tree stores fragments";
      continue;
    }
    const bool first_room = tree.fragments[r.begin].source < 4;
    for (std::uint32_t f = r.begin; f < r.end; ++f)
      EXPECT_EQ(tree.fragments[f].source < 4, first_room) << "leaf " << n << " mixes both rooms";
  }
  EXPECT_EQ(tree.stats.mixed_leaves, 0u);
}

// The four walls of one convex room, but two groups: without groups one leaf; with them,
// a free plane parts the groups and each leaf holds one.
TEST(LeafyTrees, ConvexSetOfTwoGroupsIsPartedByAFreePlane) {
  const std::vector<Polygon> segs = room(0, 0, 4, 1, 0);
  const Tree one = build(segs, "weighted", Shape::Leafy);
  EXPECT_EQ(one.nodes.size(), 1u);
  const Tree two = build(segs, "weighted", Shape::Leafy, {0, 0, 1, 1});
  EXPECT_GT(two.nodes.size(), 1u);
  EXPECT_GE(two.stats.fallbacks, 1u);
  EXPECT_EQ(two.stats.mixed_leaves, 0u);
  const std::vector<std::uint32_t> group = {0, 0, 1, 1};
  for (std::uint32_t n = 0; n < two.nodes.size(); ++n) {
    const FragmentRange r = two.fragments_of(n);
    for (std::uint32_t f = r.begin + 1; f < r.end; ++f)
      EXPECT_EQ(group[two.fragments[f].source], group[two.fragments[r.begin].source]) << "leaf " << n;
  }
}

TEST(LeafyTrees, InvariantsCatchAFlippedPlane) {
  const Scene scene = make_scene("random-segments", {{"n", "200"}, {"seed", "5"}});
  const Tree tree = build(scene.polygons, "crystal", Shape::Leafy);
  ASSERT_TRUE(check_tree_invariants(tree, scene.polygons).ok());
  std::uint32_t caught = 0, tried = 0;
  for (std::uint32_t n = 0; n < tree.nodes.size() && tried < 10; ++n) {
    if (tree.nodes[n].is_cell_leaf()) continue;
    Tree broken = tree;
    broken.nodes[n].plane = PlanePool::flip(broken.nodes[n].plane);
    ++tried;
    caught += !check_tree_invariants(broken, scene.polygons).ok();
  }
  EXPECT_EQ(caught, tried);
}

TEST(RandomSegments, SegmentsArePairwiseDisjoint) {
  const Scene scene = make_scene("random-segments", {{"n", "600"}, {"seed", "9"}, {"length", "6"}});
  ASSERT_EQ(scene.polygons.size(), 600u);
  const auto side = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  std::size_t crossings = 0;
  for (std::size_t i = 0; i < scene.polygons.size(); ++i)
    for (std::size_t j = i + 1; j < scene.polygons.size(); ++j) {
      const auto& p = scene.polygons[i].verts;
      const auto& q = scene.polygons[j].verts;
      const double d1 = side(q[0].p, q[1].p, p[0].p), d2 = side(q[0].p, q[1].p, p[1].p);
      const double d3 = side(p[0].p, p[1].p, q[0].p), d4 = side(p[0].p, p[1].p, q[1].p);
      crossings += d1 * d2 <= 0 && d3 * d4 <= 0;
    }
  EXPECT_EQ(crossings, 0u);
}

// The random autopartition of n disjoint segments makes at most n + 2n ln n fragments in
// expectation (Paterson-Yao): the mean over seeds must stay below it. Long segments make the
// bound meaningful: a broken split count or a splitter that cuts needlessly would exceed it.
TEST(RandomSegments, RandomAutopartitionStaysUnderThePatersonYaoBound) {
  const std::size_t n = 2000;
  double sum = 0;
  const int seeds = 5;
  for (int s = 1; s <= seeds; ++s) {
    const Scene scene = make_scene("random-segments", {{"n", std::to_string(n)}, {"seed", std::to_string(s)}, {"length", "16"}});
    auto splitter = make_splitter("random", {}, static_cast<std::uint64_t>(s));
    sum += static_cast<double>(build_tree(scene.polygons, *splitter).fragments.size());
  }
  const double bound = n + 2.0 * n * std::log(static_cast<double>(n));
  EXPECT_LT(sum / seeds, bound);
  EXPECT_GT(sum / seeds, 1.2 * n) << "long random segments should be split often";
}
