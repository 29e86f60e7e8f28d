// Exact solid trees and exact merging, proved at grid points against CGAL's exact side-of-mesh
// predicates on the same snapped operands (in grid coordinates, which doubles hold exactly). Each
// test names the degeneracy or the planted error it covers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <pthread.h>

#include <limits>
#include <string>
#include <vector>

#include "catalog.h"
#include "common/rng.h"
#include "geometry/snap.h"
#include "solid/exact_merge.h"
#include "solid/exact_solid_tree.h"
#include "split/registry.h"
#include "validate/exact_solid.h"
#include "validate/exact_solid_check.h"
#include "cli_runner.h"
#include <filesystem>
#include <fstream>

namespace bsp {
namespace {

const SetOp kOps[] = {SetOp::Union, SetOp::Intersection, SetOp::Difference, SetOp::SymmetricDifference};

std::vector<Polygon> scene(const std::string& name, const ParamAssignments& params) {
  return make_scene(name, params).polygons;
}

Box bounds(const std::vector<Polygon>& polys) {
  Box b;
  for (const auto& p : polys)
    for (const auto& v : p.verts) b.add(v.p);
  return b;
}

// The operand as CGAL sees it: the snapped polygons' corners in grid coordinates.
std::vector<Polygon> in_grid_units(const std::vector<Polygon>& polys, const Grid& grid) {
  const SnappedScene s = snap_polygons(polys, grid);
  std::vector<Polygon> out;
  for (const auto& corners : s.corners) {
    Polygon p;
    for (const GridPoint& q : corners)
      p.verts.push_back({{static_cast<double>(q.x), static_cast<double>(q.y), static_cast<double>(q.z)}});
    out.push_back(p);
  }
  return out;
}

struct ExactPair {
  std::vector<Polygon> a, b;
  std::unique_ptr<ExactSolidSpace> space;
  std::vector<Polygon> ga, gb;  // in grid units

  ExactPair(std::vector<Polygon> pa, std::vector<Polygon> pb)
      : a(std::move(pa)), b(std::move(pb)), space(ExactSolidSpace::for_box(solid_box(bounds(a), bounds(b)))) {
    ga = in_grid_units(a, space->grid());
    gb = in_grid_units(b, space->grid());
  }
  ExactSolidTree solid(const std::vector<Polygon>& polys, const std::string& heuristic) {
    auto splitter = make_splitter(heuristic, {}, 1);
    return build_exact_solid(polys, *splitter, *space).solid;
  }
};

struct PointProof {
  int compared = 0, on_operand = 0, mismatches = 0;
};

// Grid points uniform in the operands' box: the tree's exact answer against CGAL's.
PointProof prove_points(const ExactSolidTree& r, const ExactPair& p, SetOp op, int points = 3000) {
  const ExactSolid ea(p.ga), eb(p.gb);
  Box box = bounds(p.ga);
  box.add(bounds(p.gb));
  Rng rng(11);
  PointProof proof;
  for (int i = 0; i < points; ++i) {
    const GridPoint q{static_cast<std::int64_t>(rng.uniform(box.lo.x, box.hi.x)),
                      static_cast<std::int64_t>(rng.uniform(box.lo.y, box.hi.y)),
                      static_cast<std::int64_t>(rng.uniform(box.lo.z, box.hi.z))};
    const Vec3 x{static_cast<double>(q.x), static_cast<double>(q.y), static_cast<double>(q.z)};
    const ExactSide sa = ea.side(x), sb = eb.side(x);
    if (sa == ExactSide::Boundary || sb == ExactSide::Boundary) {
      ++proof.on_operand;
      continue;
    }
    ++proof.compared;
    const bool truth = in_result(op, sa == ExactSide::Inside, sb == ExactSide::Inside);
    proof.mismatches += classify_point(r, *p.space, q) != (truth ? PointClass::In : PointClass::Out);
  }
  return proof;
}

TEST(ExactSolidTree, CubeFacesAreOnAndNeighboursAreInOrOut) {
  ExactPair p(scene("box", {{"seed", "0"}}), scene("box", {{"seed", "0"}}));
  const ExactSolidTree s = p.solid(p.a, "first");
  const GridPoint c = *p.space->grid().snap({0, 0, 0}), face = *p.space->grid().snap({1, 0.2, 0.3});
  EXPECT_EQ(classify_point(s, *p.space, c), PointClass::In);
  EXPECT_EQ(classify_point(s, *p.space, face), PointClass::On);
  EXPECT_EQ(classify_point(s, *p.space, {face.x + 1, face.y, face.z}), PointClass::Out);
  EXPECT_EQ(classify_point(s, *p.space, {face.x - 1, face.y, face.z}), PointClass::In);
}

TEST(ExactSolidTree, EveryHeuristicBuildsASphereThatClassifiesGridPointsLikeCgal) {
  ExactPair p(scene("sphere", {{"n", "300"}}), scene("sphere", {{"n", "300"}}));
  for (const auto& h : heuristics()) {
    const ExactSolidTree s = p.solid(p.a, h.name);
    const PointProof proof = prove_points(s, p, SetOp::Intersection);  // A ∩ A = A
    EXPECT_EQ(proof.mismatches, 0) << h.name;
    EXPECT_GT(proof.compared, 2900) << h.name;
  }
}

TEST(ExactMerge, OverlappingSpheresEveryOperationAndHeuristicMatchCgal) {
  ExactPair p(scene("sphere", {{"n", "400"}}), scene("sphere", {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}}));
  for (const std::string h : {"first", "crystal", "halving", "naylor", "octree", "sah"}) {
    const ExactSolidTree a = p.solid(p.a, h), b = p.solid(p.b, h);
    for (SetOp op : kOps) {
      MergeStats stats;
      const ExactSolidTree r = merge(a, b, *p.space, op, &stats);
      const PointProof proof = prove_points(r, p, op);
      EXPECT_EQ(proof.mismatches, 0) << h << " " << set_op_name(op);
      EXPECT_GT(proof.compared, 2900) << h << " " << set_op_name(op);
      EXPECT_EQ(stats.inconsistent, 0u);
      EXPECT_LE(stats.after.nodes, stats.before.nodes);
    }
  }
}

// Pruning by bounds passes a subtree whose sub-hyperplanes lie on one side of h(t1) whole, and
// finds its leaf on the other side down one path: the tree after reduce() is the one the full
// partition makes, node for node, and the invariants and CGAL's points agree. A wrong leaf there
// (the other label, or the subtree on the wrong side) changes the tree.
TEST(ExactMerge, PruningByBoundsMakesTheSameTree) {
  ExactPair p(scene("sphere", {{"n", "600"}}), scene("torus", {{"n", "600"}, {"x", "0.6"}, {"seed", "4"}}));
  for (const std::string h : {"first", "halving", "octree"}) {
    const ExactSolidTree a = p.solid(p.a, h), b = p.solid(p.b, h);
    for (SetOp op : kOps) {
      MergeStats full, pruned;
      const ExactSolidTree r = merge(a, b, *p.space, op, &full);
      const ExactSolidTree q = merge(a, b, *p.space, op, &pruned, MergeOptions{.prune_by_bounds = true, .compaction = {}});
      EXPECT_EQ(full.pruned, 0u);
      EXPECT_GT(pruned.pruned, 0u) << h << " " << set_op_name(op);
      EXPECT_EQ(pruned.partition_nodes, full.partition_nodes) << h << " " << set_op_name(op);
      EXPECT_EQ(check_exact_solid(q, *p.space), "") << h << " " << set_op_name(op);
      ASSERT_EQ(q.nodes.size(), r.nodes.size()) << h << " " << set_op_name(op);
      EXPECT_EQ(q.root, r.root);
      for (std::size_t i = 0; i < r.nodes.size(); ++i) {
        EXPECT_EQ(q.nodes[i].plane, r.nodes[i].plane);
        EXPECT_EQ(q.nodes[i].front, r.nodes[i].front);
        EXPECT_EQ(q.nodes[i].back, r.nodes[i].back);
      }
      EXPECT_EQ(prove_points(q, p, op, 1000).mismatches, 0) << h << " " << set_op_name(op);
    }
  }
}

// As Merge.ChainOperandsCompactedMakeTheSameTree: compacting the work array often changes nothing
// in the merged tree, whose invariants (every sub-hyperplane on its plane, inside its region) hold
// and whose sub-hyperplanes have the same certified boxes, with pruning by bounds and without.
TEST(ExactMerge, ChainOperandsCompactedMakeTheSameTree) {
  constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  ExactPair p(scene("sphere", {{"n", "400"}}), scene("torus", {{"n", "400"}, {"x", "0.6"}, {"seed", "4"}}));
  for (const std::string h : {"first", "crystal", "octree"}) {
    const ExactSolidTree a = p.solid(p.a, h), b = p.solid(p.b, h);
    for (const bool prune : {false, true})
      for (SetOp op : kOps) {
        const std::string what = h + " " + std::string(set_op_name(op)) + (prune ? " pruned" : "");
        MergeStats never, often;
        const ExactSolidTree r =
            merge(a, b, *p.space, op, &never, MergeOptions{.prune_by_bounds = prune, .compaction = {.floor = kNever}});
        const ExactSolidTree q =
            merge(a, b, *p.space, op, &often, MergeOptions{.prune_by_bounds = prune, .compaction = {.floor = 0}});
        EXPECT_EQ(never.compactions, 0u);
        EXPECT_GT(often.compactions, 3u) << what;
        EXPECT_GT(often.compacted_nodes, 0u) << what;
        EXPECT_EQ(often.pruned, never.pruned) << what;
        EXPECT_EQ(often.before.nodes, never.before.nodes) << what;
        EXPECT_EQ(check_exact_solid(q, *p.space), "") << what;
        ASSERT_EQ(q.nodes.size(), r.nodes.size()) << what;
        EXPECT_EQ(q.root, r.root);
        std::size_t boxed = 0;
        for (std::size_t i = 0; i < r.nodes.size(); ++i) {
          EXPECT_EQ(q.nodes[i].plane, r.nodes[i].plane);
          EXPECT_EQ(q.nodes[i].front, r.nodes[i].front);
          EXPECT_EQ(q.nodes[i].back, r.nodes[i].back);
          const FilterBox bq = p.space->shps().box(q.shp[i]), br = p.space->shps().box(r.shp[i]);
          ASSERT_EQ(bq.bounded, br.bounded);
          boxed += bq.bounded;
          for (int k = 0; k < 3 && bq.bounded; ++k) {
            EXPECT_EQ(bq.centre[k], br.centre[k]);
            EXPECT_EQ(bq.half[k], br.half[k]);
          }
        }
        EXPECT_GT(boxed, r.nodes.size() / 2) << what;
        EXPECT_EQ(prove_points(q, p, op, 1000).mismatches, 0) << what;
      }
  }
}

TEST(ExactMerge, CoplanarFacesOfTouchingBoxes) {
  // The boxes share the plane x = 0 over a square: partitionTree's coplanar case, both facings,
  // decided by pooled index.
  ExactPair p(scene("box", {{"seed", "0"}, {"n", "24"}}), scene("box", {{"seed", "0"}, {"x", "1"}, {"y", "0.5"}}));
  const ExactSolidTree a = p.solid(p.a, "first"), b = p.solid(p.b, "first");
  for (SetOp op : kOps) {
    const ExactSolidTree r = merge(a, b, *p.space, op);
    EXPECT_EQ(prove_points(r, p, op).mismatches, 0) << set_op_name(op);
  }
}

TEST(ExactMerge, IdenticalOperandsEveryPlaneCoplanar) {
  ExactPair p(scene("menger-sponge", {{"seed", "3"}}), scene("menger-sponge", {{"seed", "3"}}));
  const ExactSolidTree a = p.solid(p.a, "naylor"), b = p.solid(p.b, "halving");
  const ExactSolidTree nothing = merge(a, b, *p.space, SetOp::Difference);
  EXPECT_EQ(nothing.root, kOut) << "A - A must reduce to one OUT leaf";
  EXPECT_EQ(merge(a, b, *p.space, SetOp::SymmetricDifference).root, kOut);
  EXPECT_EQ(prove_points(merge(a, b, *p.space, SetOp::Union), p, SetOp::Union).mismatches, 0);
}

TEST(ExactMerge, SolidWithACavityAgainstATorus) {
  ExactPair p(scene("hollow-box", {{"seed", "0"}}), scene("torus", {{"n", "800"}, {"seed", "5"}, {"x", "0.4"}}));
  const ExactSolidTree a = p.solid(p.a, "crystal"), b = p.solid(p.b, "crystal");
  for (SetOp op : kOps) EXPECT_EQ(prove_points(merge(a, b, *p.space, op), p, op).mismatches, 0) << set_op_name(op);
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

TEST(ExactMerge, ChainOperandsDeeperThanASmallStackAllows) {
  ExactPair p(scene("sphere", {{"n", "4000"}}), scene("sphere", {{"n", "4000"}, {"x", "0.5"}, {"scale", "0.9"}}));
  ExactSolidTree a, b, r;
  MergeStats stats;
  std::vector<PlanePolygon> boundary;
  on_small_stack([&] {
    a = p.solid(p.a, "first");
    b = p.solid(p.b, "first");
    r = merge(a, b, *p.space, SetOp::Intersection, &stats);
    boundary = exact_solid_boundary(r, *p.space);
  });
  EXPECT_GE(solid_size(a).depth, 1900u);
  EXPECT_GE(stats.after.depth, 1000u);
  EXPECT_GT(boundary.size(), 2000u);
  EXPECT_EQ(prove_points(r, p, SetOp::Intersection, 1000).mismatches, 0);
}

TEST(ExactMerge, SameInputsGiveTheSameTreeBitForBit) {
  ExactPair p(scene("torus", {{"n", "600"}}), scene("torus", {{"n", "600"}, {"x", "0.7"}, {"seed", "4"}}));
  const ExactSolidTree a = p.solid(p.a, "naylor"), b = p.solid(p.b, "naylor");
  const ExactSolidTree r1 = merge(a, b, *p.space, SetOp::Difference), r2 = merge(a, b, *p.space, SetOp::Difference);
  ASSERT_EQ(r1.nodes.size(), r2.nodes.size());
  EXPECT_EQ(r1.root, r2.root);
  for (std::size_t i = 0; i < r1.nodes.size(); ++i) {
    EXPECT_EQ(r1.nodes[i].plane, r2.nodes[i].plane);
    EXPECT_EQ(r1.nodes[i].front, r2.nodes[i].front);
    EXPECT_EQ(r1.nodes[i].back, r2.nodes[i].back);
    EXPECT_EQ(p.space->shps().polygon(r1.shp[i]).bounds, p.space->shps().polygon(r2.shp[i]).bounds);
  }
}

TEST(ExactSolidInvariants, HoldForBuiltAndMergedTreesAndCatchPlantedBreaks) {
  ExactPair p(scene("torus", {{"n", "300"}}), scene("torus", {{"n", "300"}, {"x", "0.6"}, {"seed", "3"}}));
  for (const std::string h : {"first", "crystal", "halving", "naylor"}) {
    const ExactSolidTree a = p.solid(p.a, h), b = p.solid(p.b, h);
    EXPECT_EQ(check_exact_solid(a, *p.space), "") << h;
    for (SetOp op : kOps) EXPECT_EQ(check_exact_solid(merge(a, b, *p.space, op), *p.space), "") << h;
  }
  ExactSolidTree t = p.solid(p.a, "crystal");
  ASSERT_GT(t.nodes.size(), 3u);
  ExactSolidTree swapped = t;  // a child's sub-hyperplane under its parent: on another plane
  std::swap(swapped.shp[0], swapped.shp[1]);
  EXPECT_NE(check_exact_solid(swapped, *p.space), "");
  ExactSolidTree twin = t;  // a child on its parent's plane
  const Ref child = !is_leaf(twin.nodes[0].front) ? twin.nodes[0].front : twin.nodes[0].back;
  twin.nodes[child].plane = PlanePool::flip(twin.nodes[0].plane);
  EXPECT_NE(check_exact_solid(twin, *p.space), "");
  ExactSolidTree cycle = t;
  cycle.nodes[child].front = 0;
  EXPECT_NE(check_exact_solid(cycle, *p.space), "");
}

// The timing loop merges again and again in one space: discarding a result gives back what it took.
TEST(ExactMerge, DiscardingAResultReturnsItsSubHyperplanes) {
  ExactPair p(scene("sphere", {{"n", "300"}}), scene("sphere", {{"n", "300"}, {"x", "0.5"}}));
  const ExactSolidTree a = p.solid(p.a, "crystal"), b = p.solid(p.b, "crystal");
  discard(merge(a, b, *p.space, SetOp::Union), a, b, *p.space);
  const std::size_t live = p.space->shps().vertices_live();
  for (int i = 0; i < 3; ++i) discard(merge(a, b, *p.space, SetOp::Union), a, b, *p.space);
  EXPECT_EQ(p.space->shps().vertices_live(), live);
}

TEST(ExactMergeCheck, CatchesAFlippedLeafLabel) {
  ExactPair p(scene("sphere", {{"n", "400"}}), scene("sphere", {{"n", "400"}, {"x", "0.5"}, {"scale", "0.9"}}));
  const ExactSolidTree a = p.solid(p.a, "naylor"), b = p.solid(p.b, "naylor");
  ExactSolidTree r = merge(a, b, *p.space, SetOp::Union);
  ASSERT_EQ(prove_points(r, p, SetOp::Union).mismatches, 0);
  // Flip the leaf holding the first sphere's centre: its whole cell changes side.
  const GridPoint centre = *p.space->grid().snap({0, 0, 0});
  Ref* link = &r.root;
  while (!is_leaf(*link)) {
    ExactSolidNode& n = r.nodes[*link];
    link = p.space->pool()[n.plane].side(centre) >= 0 ? &n.front : &n.back;
  }
  ASSERT_EQ(*link, kIn);
  *link = kOut;
  EXPECT_GT(prove_points(r, p, SetOp::Union).mismatches, 0);
}

TEST(ExactMergeCheck, CatchesAWrongTreeOpCellRow) {
  ExactPair p(scene("sphere", {{"n", "200"}}), scene("sphere", {{"n", "200"}, {"x", "0.5"}}));
  const ExactSolidTree a = p.solid(p.a, "crystal"), b = p.solid(p.b, "crystal");
  CellTable wrong = cell_table(SetOp::Union);
  wrong.first_leaf[0] = CellResult::Out;  // an OUT cell of A drops what B holds there
  EXPECT_GT(prove_points(merge_with_table(a, b, *p.space, wrong), p, SetOp::Union).mismatches, 0);
}

// ---- the whole proof: exact volume against CGAL's exact corefinement, closure, points ----------

ExactSolidCheck prove_exactly(const ExactSolidTree& r, ExactPair& p, SetOp op, std::vector<PlanePolygon> boundary) {
  SolidCheckSettings settings;
  settings.points = 2000;
  return check_exact_set_operation(r, *p.space, boundary, p.a, p.b, op, settings);
}

TEST(ExactMergeProof, VolumeIsCgalsExactVolumeAndTheBoundaryIsClosedForEveryHeuristicAndOperation) {
  ExactPair p(scene("sphere", {{"n", "300"}}), scene("sphere", {{"n", "300"}, {"x", "0.5"}, {"scale", "0.9"}}));
  for (const std::string h : {"first", "crystal", "halving", "naylor"}) {
    const ExactSolidTree a = p.solid(p.a, h), b = p.solid(p.b, h);
    for (SetOp op : kOps) {
      const ExactSolidTree r = merge(a, b, *p.space, op);
      const ExactSolidCheck c = prove_exactly(r, p, op, exact_solid_boundary(r, *p.space));
      EXPECT_TRUE(c.ok()) << h << " " << set_op_name(op) << ": mismatches " << c.mismatches << ", border segments "
                          << c.boundary.border_segments << ", volume equal " << c.volume_equal() << " "
                          << c.corefine_error;
      EXPECT_GT(c.boundary.volume.size(), 100u) << "rational, not rounded";
    }
  }
}

TEST(ExactMergeProof, CatchesAMissingBoundaryFaceAndAFlippedCell) {
  ExactPair p(scene("torus", {{"n", "400"}}), scene("torus", {{"n", "400"}, {"x", "0.6"}, {"seed", "2"}}));
  const ExactSolidTree a = p.solid(p.a, "crystal"), b = p.solid(p.b, "crystal");
  ExactSolidTree r = merge(a, b, *p.space, SetOp::Union);
  std::vector<PlanePolygon> boundary = exact_solid_boundary(r, *p.space);
  ASSERT_TRUE(prove_exactly(r, p, SetOp::Union, boundary).ok());
  boundary.pop_back();  // a hole
  const ExactSolidCheck holed = prove_exactly(r, p, SetOp::Union, boundary);
  EXPECT_GT(holed.boundary.border_segments, 0u);
  EXPECT_FALSE(holed.volume_equal());
  for (auto& n : r.nodes)  // an IN cell turned OUT: a closed boundary around the wrong volume
    if (n.back == kIn) {
      n.back = kOut;
      break;
    }
  const ExactSolidCheck flipped = prove_exactly(r, p, SetOp::Union, exact_solid_boundary(r, *p.space));
  EXPECT_TRUE(flipped.boundary.closed());
  EXPECT_FALSE(flipped.volume_equal());
}

// ---- the commands ----------------------------------------------------------------------------

TEST(ExactMergeCli, ProvesAUnionExactlyAndWritesAnObj) {
  const auto dir = testing::fresh_test_dir("exact_merge_cli");
  const auto r = testing::run_bspbench(
      "merge --a sphere --a-param n=300 --b sphere --b-param n=300 --b-param x=0.5 --op difference --heuristic halving "
      "--points 2000 --kernel exact --json --out " + (dir / "d.obj").string(), dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["kernel"], "exact");
  EXPECT_EQ(out["check"]["volume_equal"], true);
  EXPECT_EQ(out["check"]["boundary"]["border_edges"], 0);
  EXPECT_EQ(out["check"]["volume_exact"], out["check"]["corefine_volume_exact"]);
  EXPECT_TRUE(std::filesystem::exists(dir / "d.obj"));
  const auto bad = testing::run_bspbench("merge --a sphere --b sphere --op union --kernel fixed", dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--kernel must be float or exact"), std::string::npos) << bad.err;
  std::filesystem::remove_all(dir);
}

TEST(ExactClassifyCli, DecidesSnappedPointsExactlyOnTheFaceItself) {
  const auto dir = testing::fresh_test_dir("exact_classify_cli");
  {
    std::ofstream f(dir / "points.txt");
    f << "0 0 0\n5 0 0\n1 0.25 0.5\n1e300 0 0\n";
  }
  const auto r = testing::run_bspbench(
      "classify --solid box --solid-param seed=0 --kernel exact --points " + (dir / "points.txt").string(), dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "in\nout\non\nout\n");
  std::filesystem::remove_all(dir);
}

TEST(ExactCompareCli, ChecksOrdersExactlyForEveryHeuristic) {
  const auto dir = testing::fresh_test_dir("exact_compare_cli");
  const auto r = testing::run_bspbench(
      "compare --scene near-degenerate --n 200 --heuristics first,crystal --views 2 --kernel exact --json", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["kernel"], "exact");
  for (const auto& h : out["heuristics"]) {
    EXPECT_EQ(h["validation"]["order_violations"], 0);
    EXPECT_GT(h["validation"]["order_rays"], 0);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace bsp
