// Solid trees, merging and their proof against CGAL's exact geometry. Each test names the
// degeneracy or the planted error it covers.
#include <gtest/gtest.h>

#include <pthread.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <array>
#include <map>
#include <fstream>
#include <string>
#include <vector>

#include "catalog.h"
#include "cli_runner.h"
#include "common/errors.h"
#include "solid/boundary.h"
#include "solid/cells.h"
#include "solid/merge.h"
#include "solid/solid_build.h"
#include "solid/view_cull.h"
#include "metrics/traversal_cost.h"
#include "tree/build.h"
#include "validate/order_check.h"
#include "split/registry.h"
#include "validate/solid_check.h"

namespace bsp {
namespace {

std::vector<Polygon> solid_scene(const std::string& name, const ParamAssignments& params) {
  return make_scene(name, params).polygons;
}

struct Pair {
  std::vector<Polygon> a, b;
  Box box;
};

Pair make_pair_of(const std::string& name, const ParamAssignments& a, const ParamAssignments& b) {
  Pair p{solid_scene(name, a), solid_scene(name, b), {}};
  Box ba, bb;
  for (const auto& poly : p.a)
    for (const auto& v : poly.verts) ba.add(v.p);
  for (const auto& poly : p.b)
    for (const auto& v : poly.verts) bb.add(v.p);
  p.box = solid_box(ba, bb);
  return p;
}

SolidTree solid_of(const std::vector<Polygon>& polys, const std::string& heuristic, const Box& box) {
  auto splitter = make_splitter(heuristic, {}, 1);
  return build_solid(polys, *splitter, box).solid;
}

SolidCheck prove(const SolidTree& result, const Pair& p, SetOp op, std::uint64_t points = 4000) {
  const ExactSolid ea(p.a), eb(p.b);
  SolidCheckSettings settings;
  settings.points = points;
  return check_set_operation(result, ea, eb, p.a, p.b, op, settings);
}

const SetOp kOps[] = {SetOp::Union, SetOp::Intersection, SetOp::Difference, SetOp::SymmetricDifference};

// ---- solid trees -----------------------------------------------------------------------------

TEST(SolidTree, EveryHeuristicBuildsASphereThatClassifiesPointsLikeCgal) {
  const auto sphere = solid_scene("sphere", {{"n", "300"}});
  Box b;
  for (const auto& poly : sphere)
    for (const auto& v : poly.verts) b.add(v.p);
  const Box box = solid_box(b, b);
  const ExactSolid exact(sphere);
  for (const auto& h : heuristics()) {
    const SolidTree s = solid_of(sphere, h.name, box);
    EXPECT_EQ(classify_point(s, {0, 0, 0}), PointClass::In) << h.name;
    EXPECT_EQ(classify_point(s, {0, 0, 1.5}), PointClass::Out) << h.name;
    Rng rng(7);
    int wrong = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p{rng.uniform(-1.1, 1.1), rng.uniform(-1.1, 1.1), rng.uniform(-1.1, 1.1)};
      if (exact.distance(p) <= s.tol.plane_eps) continue;
      wrong += classify_point(s, p) != (exact.side(p) == ExactSide::Inside ? PointClass::In : PointClass::Out);
    }
    EXPECT_EQ(wrong, 0) << h.name;
    EXPECT_NEAR(solid_volume(s), exact.volume(), 1e-12 * exact.volume()) << h.name;
  }
}

TEST(SolidTree, PointOnAFaceIsOn) {
  const auto box_polys = solid_scene("box", {{"seed", "0"}});
  Box b{{-1, -1, -1}, {1, 1, 1}};
  const SolidTree s = solid_of(box_polys, "first", solid_box(b, b));
  EXPECT_EQ(classify_point(s, {1, 0.2, 0.3}), PointClass::On);
  EXPECT_EQ(classify_point(s, {0.999, 0.2, 0.3}), PointClass::In);
}

TEST(SolidTree, ConvexSolidAutopartitionIsAChainHalvingIsNot) {
  const auto sphere = solid_scene("sphere", {{"n", "1000"}});
  Box b;
  for (const auto& poly : sphere)
    for (const auto& v : poly.verts) b.add(v.p);
  const SolidSize chain = solid_size(solid_of(sphere, "first", solid_box(b, b)));
  const SolidSize halving = solid_size(solid_of(sphere, "halving", solid_box(b, b)));
  // Every face plane leaves the rest of a convex solid behind it: one IN cell, depth = planes.
  EXPECT_EQ(chain.in_leaves, 1u);
  EXPECT_EQ(chain.depth, chain.nodes);
  EXPECT_LT(halving.depth * 4, chain.depth);
}

// The octree front end cuts a convex solid on axis-aligned lattice planes until cells hold at most
// leaf_faces faces: shallow where the autopartition is a chain, and two operands whose extents are
// alike get the same top planes (a lattice point needs no box), which merging meets as coplanar
// nodes: partitioning visits a small fraction of the nodes the chains make it visit.
TEST(SolidTree, OctreeSolidIsShallowAndOperandsShareItsTopPlanes) {
  const Pair p = make_pair_of("sphere", {{"n", "2000"}}, {{"n", "2000"}, {"x", "0.3"}, {"scale", "0.9"}});
  const SolidTree chain_a = solid_of(p.a, "first", p.box), chain_b = solid_of(p.b, "first", p.box);
  const SolidTree a = solid_of(p.a, "octree", p.box), b = solid_of(p.b, "octree", p.box);
  EXPECT_LT(solid_size(a).depth * 4, solid_size(chain_a).depth);
  // The root parts the sphere at x = 0 for both: 0 is the coarsest lattice point in the middle half
  // of x in [-1, 1] and of x in [-0.6, 1.2].
  ASSERT_FALSE(is_leaf(a.root));
  ASSERT_FALSE(is_leaf(b.root));
  EXPECT_EQ(a.nodes[a.root].plane, (Plane{{1, 0, 0}, 0}));
  EXPECT_EQ(b.nodes[b.root].plane, a.nodes[a.root].plane);
  // Below the root every plane is axis-aligned down to cells of at most 64 faces (leaf_faces): a
  // node's plane is axis-aligned exactly when it is not a face's (a sphere has no axis-aligned face).
  std::size_t axis_aligned = 0;
  for (const SolidNode& n : a.nodes) {
    const int zeros = (n.plane.n.x == 0) + (n.plane.n.y == 0) + (n.plane.n.z == 0);
    axis_aligned += zeros == 2;
  }
  EXPECT_GE(axis_aligned, 2000u / 64);
  MergeStats octree, chain;
  const SolidTree r = merge(a, b, SetOp::Union, &octree);
  merge(chain_a, chain_b, SetOp::Union, &chain);
  EXPECT_LT(octree.partition_nodes * 10, chain.partition_nodes);
  const SolidCheck c = prove(r, p, SetOp::Union);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(c.boundary.edges.border_edges, 0u);
}

// The float kernel's pruning by bounds: a subtree farther than plane_eps from h(t1) goes whole, its
// leaf beyond found down one path; the reduced tree is the full partition's, node for node.
TEST(Merge, PruningByBoundsMakesTheSameTree) {
  const Pair p = make_pair_of("sphere", {{"n", "600"}}, {{"n", "600"}, {"x", "0.5"}, {"scale", "0.9"}});
  for (const std::string h : {"first", "halving", "octree"}) {
    const SolidTree a = solid_of(p.a, h, p.box), b = solid_of(p.b, h, p.box);
    for (SetOp op : kOps) {
      MergeStats full, pruned;
      const SolidTree r = merge(a, b, op, &full);
      const SolidTree q = merge(a, b, op, &pruned, MergeOptions{.prune_by_bounds = true, .compaction = {}});
      EXPECT_EQ(full.pruned, 0u);
      EXPECT_GT(pruned.pruned, 0u) << h << " " << set_op_name(op);
      EXPECT_EQ(pruned.partition_nodes, full.partition_nodes) << h << " " << set_op_name(op);
      ASSERT_EQ(q.nodes.size(), r.nodes.size()) << h << " " << set_op_name(op);
      for (std::size_t i = 0; i < r.nodes.size(); ++i) {
        EXPECT_EQ(q.nodes[i].plane, r.nodes[i].plane);
        EXPECT_EQ(q.nodes[i].front, r.nodes[i].front);
        EXPECT_EQ(q.nodes[i].back, r.nodes[i].back);
      }
      EXPECT_EQ(prove(q, p, op, 1000).mismatches, 0u) << h << " " << set_op_name(op);
    }
  }
}

// Chains (an autopartition of a convex solid) leave the most garbage: partitioned again at every
// node of A, each part of B is referenced once. Compacting the work array whenever more than twice
// what was live has been made keeps only what the pending parts and results reach; the merged tree
// is the same node for node and loop for loop, with pruning by bounds (whose boxes of moved nodes
// are forgotten) and without, and the compactions reclaim nodes.
TEST(Merge, ChainOperandsCompactedMakeTheSameTree) {
  constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  const Pair p = make_pair_of("sphere", {{"n", "400"}}, {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}});
  for (const std::string h : {"first", "crystal", "octree"}) {
    const SolidTree a = solid_of(p.a, h, p.box), b = solid_of(p.b, h, p.box);
    for (const bool prune : {false, true})
      for (SetOp op : kOps) {
        const std::string what = h + " " + std::string(set_op_name(op)) + (prune ? " pruned" : "");
        MergeStats never, often;
        const SolidTree r = merge(a, b, op, &never, MergeOptions{.prune_by_bounds = prune, .compaction = {.floor = kNever}});
        const SolidTree q = merge(a, b, op, &often, MergeOptions{.prune_by_bounds = prune, .compaction = {.floor = 0}});
        EXPECT_EQ(never.compactions, 0u);
        EXPECT_GT(often.compactions, 3u) << what;
        EXPECT_GT(often.compacted_nodes, 0u) << what;
        EXPECT_EQ(often.pruned, never.pruned) << what;
        EXPECT_EQ(often.before.nodes, never.before.nodes) << what;
        ASSERT_EQ(q.nodes.size(), r.nodes.size()) << what;
        EXPECT_EQ(q.root, r.root);
        for (std::size_t i = 0; i < r.nodes.size(); ++i) {
          EXPECT_EQ(q.nodes[i].plane, r.nodes[i].plane);
          EXPECT_EQ(q.nodes[i].front, r.nodes[i].front);
          EXPECT_EQ(q.nodes[i].back, r.nodes[i].back);
          const auto lq = q.loops[q.shp[i]], lr = r.loops[r.shp[i]];
          ASSERT_EQ(lq.size(), lr.size());
          EXPECT_TRUE(std::equal(lq.begin(), lq.end(), lr.begin()));
        }
        EXPECT_EQ(prove(q, p, op, 1000).mismatches, 0u) << what;
      }
  }
}

// The SAH front end cuts off empty space: with a sphere of 800 faces far left of one of 200, the
// cheapest binned plane at the root is the first bin bound past the big sphere, which leaves it the
// smallest part; the box's midpoint (-1.25) or octree's lattice point (0) would cut the gap where
// the SAH costs more. Merging its trees is proved like the others'.
TEST(SolidTree, SahSolidCutsOffEmptySpaceAndMergesProved) {
  std::vector<Polygon> far = solid_scene("sphere", {{"n", "800"}, {"x", "-6"}});
  Box left;
  for (const auto& poly : far)
    for (const auto& v : poly.verts) left.add(v.p);
  const std::vector<Polygon> right = solid_scene("sphere", {{"n", "200"}, {"x", "4"}, {"scale", "0.5"}});
  far.insert(far.end(), right.begin(), right.end());
  Box b;
  for (const auto& poly : far)
    for (const auto& v : poly.verts) b.add(v.p);
  const SolidTree t = solid_of(far, "sah", solid_box(b, b));
  ASSERT_FALSE(is_leaf(t.root));
  const SolidNode& root = t.nodes[t.root];
  EXPECT_EQ(root.plane.n, (Vec3{1, 0, 0}));
  const double extent = b.hi.x - b.lo.x;  // 16 bins (sah's default) over the faces' box
  const double k = std::ceil((left.hi.x - b.lo.x) / (extent / 16));
  EXPECT_DOUBLE_EQ(-root.plane.d, b.lo.x + extent * k / 16);
  const SolidSize chain = solid_size(solid_of(far, "first", solid_box(b, b)));
  EXPECT_LT(solid_size(t).depth * 4, chain.depth);
  const Pair p = make_pair_of("sphere", {{"n", "1000"}}, {{"n", "1000"}, {"x", "0.5"}, {"scale", "0.9"}});
  const SolidTree sa = solid_of(p.a, "sah", p.box), sb = solid_of(p.b, "sah", p.box);
  for (SetOp op : kOps) {
    const SolidCheck c = prove(merge(sa, sb, op), p, op);
    EXPECT_EQ(c.mismatches, 0u) << set_op_name(op);
    EXPECT_EQ(c.boundary.edges.border_edges, 0u) << set_op_name(op);
  }
}

TEST(SolidInput, OpenOrMisorientedMeshesAreRefusedWithTheCount) {
  auto box = solid_scene("box", {{"seed", "0"}});
  EXPECT_NO_THROW(require_closed_solid(box, 1e-9, "box"));
  auto open = box;
  open.pop_back();
  try {
    require_closed_solid(open, 1e-9, "open-box");
    FAIL() << "an open box was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "open-box: not a closed solid: 4 border edges");
  }
  auto flipped = box;
  std::reverse(flipped[0].verts.begin(), flipped[0].verts.end());
  EXPECT_THROW(require_closed_solid(flipped, 1e-9, "flipped-face"), InputError);
  auto inward = box;
  for (auto& p : inward) std::reverse(p.verts.begin(), p.verts.end());
  try {
    require_closed_solid(inward, 1e-9, "inward");
    FAIL() << "an inward facing box was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("faces point inwards"), std::string::npos) << e.what();
  }
}

// ---- merging, proved -------------------------------------------------------------------------

TEST(Merge, OverlappingSpheresEveryOperationAndHeuristicMatchCgal) {
  const Pair p = make_pair_of("sphere", {{"n", "400"}}, {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}});
  for (const std::string h : {"first", "crystal", "halving", "naylor", "octree"}) {
    const SolidTree a = solid_of(p.a, h, p.box), b = solid_of(p.b, h, p.box);
    for (SetOp op : kOps) {
      MergeStats stats;
      const SolidTree r = merge(a, b, op, &stats);
      const SolidCheck c = prove(r, p, op);
      EXPECT_EQ(c.mismatches, 0u) << h << " " << set_op_name(op);
      EXPECT_LE(c.volume_relative_error, kVolumeRelativeTolerance) << h << " " << set_op_name(op);
      EXPECT_EQ(c.boundary.edges.border_edges, 0u) << h << " " << set_op_name(op);
      EXPECT_LE(stats.after.nodes, stats.before.nodes);
      EXPECT_GT(c.compared, 3000u);
    }
  }
}

TEST(Merge, CoplanarFacesOfTouchingBoxes) {
  // The boxes share the plane x = 0 over a square: partitionTree's coplanar case, both facings.
  const Pair p = make_pair_of("box", {{"seed", "0"}, {"n", "24"}}, {{"seed", "0"}, {"x", "1"}, {"y", "0.5"}});
  const SolidTree a = solid_of(p.a, "first", p.box), b = solid_of(p.b, "first", p.box);
  for (SetOp op : kOps) {
    const SolidCheck c = prove(merge(a, b, op), p, op);
    EXPECT_TRUE(c.ok(kVolumeRelativeTolerance)) << set_op_name(op) << " " << c.mismatches << " "
                                                << c.volume_relative_error << " " << c.boundary.edges.border_edges;
  }
}

TEST(Merge, IdenticalOperandsEveryPlaneCoplanar) {
  const Pair p = make_pair_of("menger-sponge", {{"seed", "3"}}, {{"seed", "3"}});
  const SolidTree a = solid_of(p.a, "naylor", p.box), b = solid_of(p.b, "halving", p.box);
  const double v = solid_volume(a);
  EXPECT_NEAR(solid_volume(merge(a, b, SetOp::Union)), v, 1e-12 * v);
  EXPECT_NEAR(solid_volume(merge(a, b, SetOp::Intersection)), v, 1e-12 * v);
  const SolidTree nothing = merge(a, b, SetOp::Difference);
  EXPECT_NEAR(solid_volume(nothing), 0.0, 1e-12 * v);
  EXPECT_EQ(solid_size(nothing).nodes, 0u) << "A - A must reduce to one OUT leaf";
  EXPECT_EQ(nothing.root, kOut);
}

TEST(Merge, SolidWithACavityAgainstATorus) {
  const Pair p = make_pair_of("hollow-box", {{"seed", "0"}}, {{"n", "800"}, {"seed", "5"}, {"x", "0.4"}});
  const SolidTree a = solid_of(p.a, "crystal", p.box), b = solid_of(p.b, "crystal", p.box);
  for (SetOp op : kOps) EXPECT_TRUE(prove(merge(a, b, op), p, op).ok(kVolumeRelativeTolerance)) << set_op_name(op);
}

// Runs f on a thread with a 256 KB stack: a recursive walk of a chain thousands deep overflows it.
template <class F>
void on_small_stack(F f) {
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, 256 * 1024);
  pthread_t thread;
  ASSERT_EQ(pthread_create(&thread, &attr, [](void* arg) -> void* { (*static_cast<F*>(arg))(); return nullptr; }, &f), 0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attr);
}

TEST(Merge, ChainOperandsDeeperThanASmallStackAllows) {
  // first on a sphere: a chain as deep as the sphere has face planes; building its solid,
  // merging, reducing and cutting cells walk it with explicit stacks.
  const Pair p = make_pair_of("sphere", {{"n", "6000"}}, {{"n", "6000"}, {"x", "0.5"}, {"scale", "0.9"}});
  SolidTree a, b, r;
  MergeStats stats;
  double volume = 0;
  on_small_stack([&] {
    a = solid_of(p.a, "first", p.box);
    b = solid_of(p.b, "first", p.box);
    r = merge(a, b, SetOp::Intersection, &stats);
    volume = solid_volume(r);
  });
  EXPECT_GE(solid_size(a).depth, 2900u);
  EXPECT_GE(stats.after.depth, 1500u);
  const ExactSolid ea(p.a), eb(p.b);
  EXPECT_NEAR(volume, corefine(ea, eb, SetOp::Intersection).volume, 1e-9 * volume);
}

TEST(Merge, SameInputsGiveTheSameTreeBitForBit) {
  const Pair p = make_pair_of("torus", {{"n", "600"}}, {{"n", "600"}, {"x", "0.7"}, {"seed", "4"}});
  const SolidTree a = solid_of(p.a, "naylor", p.box), b = solid_of(p.b, "naylor", p.box);
  const SolidTree r1 = merge(a, b, SetOp::Difference), r2 = merge(a, b, SetOp::Difference);
  ASSERT_EQ(r1.nodes.size(), r2.nodes.size());
  EXPECT_EQ(r1.root, r2.root);
  for (std::size_t i = 0; i < r1.nodes.size(); ++i) {
    EXPECT_EQ(r1.nodes[i].plane, r2.nodes[i].plane);
    EXPECT_EQ(r1.nodes[i].front, r2.nodes[i].front);
    EXPECT_EQ(r1.nodes[i].back, r2.nodes[i].back);
  }
}

TEST(Merge, OperandsFromDifferentBoxesAreRejected) {
  const auto s = solid_scene("sphere", {{"n", "100"}});
  const SolidTree a = solid_of(s, "first", {{-2, -2, -2}, {2, 2, 2}});
  const SolidTree b = solid_of(s, "first", {{-3, -3, -3}, {3, 3, 3}});
  EXPECT_THROW(merge(a, b, SetOp::Union), std::invalid_argument);
}

// ---- the checks catch planted errors ----------------------------------------------------------

TEST(SolidCheck, CatchesAFlippedLeafLabel) {
  const Pair p = make_pair_of("sphere", {{"n", "400"}}, {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}});
  const SolidTree a = solid_of(p.a, "naylor", p.box), b = solid_of(p.b, "naylor", p.box);
  SolidTree r = merge(a, b, SetOp::Union);
  ASSERT_TRUE(prove(r, p, SetOp::Union).ok(kVolumeRelativeTolerance));
  // Flip the IN leaf with the largest cell: a point check and the volume check must both see it.
  for (SolidNode& n : r.nodes)
    if (n.back == kIn) {
      n.back = kOut;
      break;
    }
  const SolidCheck c = prove(r, p, SetOp::Union, 20000);
  EXPECT_GT(c.volume_relative_error, kVolumeRelativeTolerance);
  EXPECT_FALSE(c.ok(kVolumeRelativeTolerance));
}

TEST(SolidCheck, CatchesAWrongTreeOpCellRow) {
  const Pair p = make_pair_of("sphere", {{"n", "400"}}, {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}});
  const SolidTree a = solid_of(p.a, "halving", p.box), b = solid_of(p.b, "halving", p.box);
  CellTable wrong = cell_table(SetOp::Difference);
  wrong.first_leaf[1] = CellResult::Tree;  // IN - T = T instead of its complement
  const SolidCheck c = prove(merge_with_table(a, b, wrong), p, SetOp::Difference);
  EXPECT_GT(c.mismatches, 100u);
  EXPECT_GT(c.volume_relative_error, 1e-3);
  EXPECT_FALSE(c.ok(kVolumeRelativeTolerance));
}

TEST(SolidCheck, CatchesAnOpenBoundary) {
  const Pair p = make_pair_of("sphere", {{"n", "400"}}, {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}});
  const SolidTree r = merge(solid_of(p.a, "crystal", p.box), solid_of(p.b, "crystal", p.box), SetOp::Union);
  const LoopPool faces = solid_boundary(r);
  EXPECT_TRUE(check_boundary(faces, r.tol.plane_eps).edges.closed());
  // Drop the largest face (small ones may be slivers that welding removes anyway).
  std::uint32_t largest = 0;
  for (std::uint32_t f = 1; f < faces.size(); ++f)
    if (length(newell_normal(faces[f])) > length(newell_normal(faces[largest]))) largest = f;
  LoopPool missing_one;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    if (f != largest) missing_one.add(faces[f]);
  EXPECT_FALSE(check_boundary(missing_one, r.tol.plane_eps).edges.closed());
}

TEST(MeshWeld, TJunctionsAreSplitSoNeighboursShareEdges) {
  // A unit square next to two half squares: the big one's edge has the halves' middle vertex on it.
  LoopPool loops;
  const std::vector<Vec3> big = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Vec3> low = {{1, 0, 0}, {2, 0, 0}, {2, 0.5, 0}, {1, 0.5, 0}};
  const std::vector<Vec3> high = {{1, 0.5, 0}, {2, 0.5, 0}, {2, 1, 0}, {1, 1, 0}};
  loops.add(big);
  loops.add(low);
  loops.add(high);
  WeldResult w = weld_loops(loops, 1e-12);
  const EdgeReport before = edge_report(w.mesh);
  EXPECT_EQ(split_t_junctions(w.mesh, 1e-12), 1u);
  const EdgeReport after = edge_report(w.mesh);
  // The shared stretch x = 1 is one edge before the split, two after, both used both ways.
  EXPECT_EQ(before.border_edges, 10u);
  EXPECT_EQ(after.border_edges, 7u);
}

// ---- the command -----------------------------------------------------------------------------

TEST(MergeCli, ProvesAUnionAndWritesAClosedObj) {
  const auto dir = testing::fresh_test_dir("merge_cli");
  const auto r = testing::run_bspbench(
      "merge --a sphere --a-param n=500 --b sphere --b-param n=500 --b-param x=0.5 --op union --heuristic naylor "
      "--points 2000 --json --out " + (dir / "u.obj").string(), dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"mismatches\":0"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "u.obj"));
  std::filesystem::remove_all(dir);
}

TEST(MergeCli, OpenMeshFileIsOneLineExitTwoNoOutput) {
  const auto dir = testing::fresh_test_dir("merge_cli");
  {
    std::ofstream f(dir / "open.off");
    f << "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n";
  }
  const auto r = testing::run_bspbench("merge --a " + (dir / "open.off").string() +
                                           " --b sphere --op union --out " + (dir / "r.obj").string(),
                                       dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("open.off: not a closed solid: 4 border edges"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "r.obj"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace bsp

// ---- view-volume culling by merging ------------------------------------------------------------

namespace bsp {
namespace {

// Whether a fragment reaches into the frustum by more than eps: what is left of it after cutting
// away, by exact signs, everything in front of each outward plane, measured by its width.
bool meets_frustum(const FragmentView& frag, const std::vector<Plane>& outward, double eps) {
  std::vector<Vec3> loop(frag.p.begin(), frag.p.end()), inside, outside;
  for (const Plane& p : outward) {
    if (loop.empty()) return false;
    split_loop(loop, p.flipped(), 0.0, inside, outside);
    loop.swap(inside);
  }
  if (loop.size() < 3) return false;
  double longest = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) longest = std::max(longest, length(loop[(i + 1) % loop.size()] - loop[i]));
  return longest > 0 && 0.5 * length(newell_normal(loop)) / longest > eps;
}

struct MergeCullResult {
  std::uint64_t views = 0, emitted = 0, corner_emitted = 0, missed = 0, not_subsequence = 0, left_out_meeting = 0;
  std::uint64_t violations = 0;
};

MergeCullResult check_merge_culling(const Tree& tree, std::uint32_t views) {
  MergeCullResult r;
  for (const Frustum& f : metric_views(tree.bounds, views)) {
    ++r.views;
    const auto merged = merged_visibility_order(tree, f);
    const auto corners = culled_visibility_order(tree, f);
    r.emitted += merged.size();
    r.corner_emitted += corners.size();
    // A subsequence of the corner-culled order.
    auto it = corners.begin();
    for (auto i : merged) {
      it = std::find(it, corners.end(), i);
      if (it == corners.end()) {
        ++r.not_subsequence;
        break;
      }
    }
    const auto planes = frustum_planes(f);
    std::vector<bool> in_merged(tree.fragments.size());
    for (auto i : merged) in_merged[i] = true;
    for (std::uint32_t i = 0; i < tree.fragments.size(); ++i)
      if (!in_merged[i] && meets_frustum(tree.fragments[i], planes, tree.tol.plane_eps)) ++r.missed;
    // The order of what it emits, against Embree.
    std::vector<Polygon> polys;
    for (auto i : merged) {
      Polygon p;
      for (const Vec3& v : tree.fragments[i].p) p.verts.push_back({v});
      polys.push_back(std::move(p));
    }
    std::vector<std::uint32_t> order(polys.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    ValidationSettings quick;
    quick.grid = 24;
    if (!polys.empty()) r.violations += validate_order(polys, f.eye, order, quick).violations;
  }
  return r;
}

class MergeCulling : public ::testing::TestWithParam<std::string> {};

TEST_P(MergeCulling, EmitsEveryFragmentInViewInOrderAndNoMoreThanTheCornerTest) {
  for (Shape shape : {Shape::Strict, Shape::Coarse}) {
    const Scene scene = make_scene(GetParam(), {{"n", "300"}});
    auto splitter = make_splitter("random", {}, 1);
    BuildOptions options;
    options.shape = shape;
    const Tree tree = build_tree(scene.polygons, *splitter, options);
    const MergeCullResult r = check_merge_culling(tree, 6);
    EXPECT_EQ(r.missed, 0u) << "fragments meeting the frustum left out";
    EXPECT_EQ(r.not_subsequence, 0u) << "emitted out of the corner-culled order";
    EXPECT_EQ(r.violations, 0u) << "Embree order violations";
    EXPECT_LE(r.emitted, r.corner_emitted);
  }
}

INSTANTIATE_TEST_SUITE_P(Catalog, MergeCulling, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const auto& g : generators())
                             if (!g.closed_solid && !g.segments) names.push_back(g.name);
                           return names;
                         }()),
                         [](const auto& info) {
                           std::string s = info.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

TEST(MergeCullingCheck, CorruptedTreeLosesFragmentsInView) {
  const Scene scene = make_scene("random-triangles", {{"n", "400"}});
  auto splitter = make_splitter("random", {}, 1);
  Tree tree = build_tree(scene.polygons, *splitter);
  ASSERT_EQ(check_merge_culling(tree, 8).missed, 0u);
  std::swap(tree.nodes[0].front, tree.nodes[0].back);
  EXPECT_GT(check_merge_culling(tree, 8).missed, 0u);
}

TEST(MergeCullingCheck, CullsMoreThanTheCornerTestOnALevel) {
  const Scene scene = make_scene("architecture", {{"n", "2000"}});
  auto splitter = make_splitter("crystal", {}, 1);
  const Tree tree = build_tree(scene.polygons, *splitter);
  const MergeCullResult r = check_merge_culling(tree, 8);
  RecordProperty("emitted_by_merging", std::to_string(r.emitted));
  RecordProperty("emitted_by_corner_test", std::to_string(r.corner_emitted));
  EXPECT_EQ(r.missed, 0u);
  EXPECT_LT(r.emitted, r.corner_emitted) << "regions the volume does not reach should be skipped";
}

}  // namespace
}  // namespace bsp

namespace bsp {
namespace {

TEST(ClassifyCli, AnswersPointQueriesAndRefusesABadPointsFile) {
  const auto dir = testing::fresh_test_dir("classify_cli");
  {
    std::ofstream f(dir / "points.txt");
    f << "# centre, far away, on a face\n0 0 0\n5 0 0\n\n1 0.25 0.5\n";
  }
  const auto r = testing::run_bspbench("classify --solid box --solid-param seed=0 --points " + (dir / "points.txt").string(), dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "in\nout\non\n");
  {
    std::ofstream f(dir / "bad.txt");
    f << "0 0 0\n1 2\n";
  }
  const auto bad = testing::run_bspbench("classify --solid box --points " + (dir / "bad.txt").string(), dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("bad.txt: line 2: expected three finite numbers"), std::string::npos) << bad.err;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace bsp

namespace bsp {
namespace {

TEST(MergeCli, SelfIntersectingMeshIsRefused) {
  // Two overlapping tetrahedra in one file: closed and outward facing, but not the boundary of a
  // solid (CGAL's volume counts the overlap twice; a solid tree would count it once).
  const auto dir = testing::fresh_test_dir("merge_cli");
  {
    std::ofstream f(dir / "two.off");
    f << "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.2 0.2 0.2\n1.2 0.2 0.2\n0.2 1.2 0.2\n0.2 0.2 1.2\n"
         "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n";
  }
  const auto r = testing::run_bspbench("merge --a " + (dir / "two.off").string() + " --b sphere --op union", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("two.off: not the boundary of a solid:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pairs of faces intersect"), std::string::npos) << r.err;
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

// Every directed edge of a cell's faces, by exact coordinates, has its reverse in another face.
bool closed_cell(const Cell& cell) {
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> balance;
  const auto key = [](const Vec3& p) { return std::array<double, 3>{p.x, p.y, p.z}; };
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) {
    const auto loop = cell.faces[i];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3 &p = loop[k], &q = loop[(k + 1) % loop.size()];
      if (p == q) continue;
      ++balance[{key(p), key(q)}];
      --balance[{key(q), key(p)}];
    }
  }
  return std::all_of(balance.begin(), balance.end(), [](const auto& e) { return e.second == 0; });
}

}  // namespace

// A cell cut by a plane in general position, through a vertex, along an edge and a hair off a
// vertex: both parts are closed polytopes (their caps chain from the faces' chords), the caps face
// out of their parts, and the volumes add up to the cell's.
TEST(CellSplit, GeneralVertexEdgeAndNearVertexPlanesGiveTwoClosedPartsThatTileTheCell) {
  const Cell cell = box_cell({{-1, -1, -1}, {1, 1, 1}});
  const std::vector<Plane> planes = {
      Plane::through(normalize(Vec3{0.3, 0.5, 0.8}), {0.1, 0.0, 0.2}),
      Plane::through(normalize(Vec3{1, 1, 1}), {1, 1, -1}),           // through the vertex (1,1,-1)
      Plane::through(normalize(Vec3{1, 1, 0}), {1, -1, 0}),           // along the edge x = 1, y = -1
      Plane::through(normalize(Vec3{1, 2, 3}), {1, 1, 1 - 1e-12}),    // a hair below the vertex (1,1,1)
  };
  for (const Plane& plane : planes) {
    SCOPED_TRACE(::testing::Message() << plane.n.x << " " << plane.n.y << " " << plane.n.z << " " << plane.d);
    Cell front, back;
    split_cell(cell, plane, 0, front, back);
    ASSERT_FALSE(front.outward.empty());
    ASSERT_FALSE(back.outward.empty());
    EXPECT_TRUE(closed_cell(front));
    EXPECT_TRUE(closed_cell(back));
    EXPECT_NEAR(cell_volume(front) + cell_volume(back), cell_volume(cell), 1e-12 * cell_volume(cell));
    EXPECT_GT(cell_volume(front), 0);
    EXPECT_GT(cell_volume(back), 0);
    // The cap is the last face of each part; it faces out of its part: along the plane's normal
    // for the back part, against it for the front.
    EXPECT_GT(dot(newell_normal(back.faces[back.faces.size() - 1]), plane.n), 0);
    EXPECT_LT(dot(newell_normal(front.faces[front.faces.size() - 1]), plane.n), 0);
  }
}

}  // namespace bsp
