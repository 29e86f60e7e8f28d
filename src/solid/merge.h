#pragma once
// Set operations on solid trees by merging [Naylor1990; Chrysanthou §4]: the second tree is
// inserted into the first, partitioned at every node of the first by that node's sub-hyperplane
// (partitionTree, §4.1), and combined with the first tree's cells by treeOpCell (Table 2.1).
// Explicit stacks throughout: a chain-shaped operand is as deep as its mesh has faces.
//
// Notation: t1 is a node of the first tree A; T is the part of the second tree B inside r(t1);
// T+ and T- are T's parts in front of and behind h(t1). s_T is where shp(T) lies against h(t1),
// s_h where shp(t1) lies against h(T) (front, back, both, on). The 7 classifications of
// [Chrysanthou §4.1, Figure 6] group as: shp(t1) in one subtree of T (s_h front or back, with
// s_T front or back: 4 cases), in both (s_h and s_T both spanning), coplanar (same or opposite
// facing).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "solid/compaction.h"
#include "solid/solid_tree.h"

namespace bsp {

enum class SetOp : std::uint8_t { Union, Intersection, Difference, SymmetricDifference };
std::string_view set_op_name(SetOp op);
SetOp parse_set_op(std::string_view name);  // union|intersection|difference|xor; throws UsageError

// treeOpCell as a table [Chrysanthou Table 2.1]: what a leaf of one operand combined with the
// other operand's tree (or leaf) T becomes.
enum class CellResult : std::uint8_t { Out, In, Tree, Complement };
struct CellTable {
  CellResult first_leaf[2];   // A's leaf (index 0 OUT, 1 IN) with T from B
  CellResult second_leaf[2];  // B's leaf (index 0 OUT, 1 IN) with T from A
};
CellTable cell_table(SetOp op);

// What a merge did, for measuring merge cost.
struct MergeStats {
  std::uint64_t partition_calls = 0;  // partitionTree calls (one per internal node pair reached)
  std::uint64_t partition_nodes = 0;  // nodes of B visited while partitioning
  std::uint64_t shp_splits = 0;       // sub-hyperplanes cut in two (of A's nodes and of B's)
  std::uint64_t merge_nodes = 0;      // merge steps (pairs of a node of A and a part of B)
  std::uint64_t cell_ops = 0;         // treeOpCell calls
  std::uint64_t complement_nodes = 0; // nodes copied to complement a subtree
  // Subtrees of T passed whole to one side of h(t1) because the box of their sub-hyperplanes lies
  // there: the other side is the one leaf the subtree has there, found down one path, and nothing
  // below is partitioned or copied (MergeOptions::prune_by_bounds).
  std::uint64_t pruned = 0;
  std::uint64_t compactions = 0;      // times the work array's garbage was collected (compaction.h)
  std::uint64_t compacted_nodes = 0;  // made nodes those compactions reclaimed
  // Places where the tolerance decisions disagreed with each other (shp(t1) spanning h(T) while
  // shp(T) did not span h(t1), or the reverse): resolved by the farther side; the region involved
  // is within plane_eps of both planes.
  std::uint64_t inconsistent = 0;
  SolidSize before;  // the merged tree as built (parts and merge steps of one leaf already collapsed)
  SolidSize after;   // after reduce()
  double merge_seconds = 0;
  double reduce_seconds = 0;
};

// Pruning by bounds [NehringWirxel2021; BernsteinFussell2009: merge only where the operands meet]:
// a subtree of T whose sub-hyperplanes all lie on one side of h(t1) (their box, a side array the
// partition fills as it meets nodes, misses h(t1)) has no node on the other side, so its part
// there is one leaf, found down one path, and the subtree goes to its side whole instead of as
// copies of the nodes on that path. (In the float kernel a node whose sub-hyperplane the tolerance
// emptied goes along whole too, where the full partition places its other child by the farther
// side; both are within plane_eps of h(t1).) Off by default: partitionTree already descends only where
// shp(t1) reaches, and a sub-hyperplane spans its node's region, so pruning visits exactly the
// nodes it would have (MergeStats::partition_nodes is equal on every measured pair) and computing
// the boxes costs more than the copies it saves (docs/solids.md).
struct MergeOptions {
  bool prune_by_bounds = false;
  CompactionPolicy compaction;  // when the work array's garbage is collected (compaction.h)
};

// partitionTree (§4.1) on its own: the parts of tree T (a subtree of `work`) in front of and behind
// plane h, given h's sub-hyperplane inside r(T) as a loop of work.loops. New nodes and loops are
// appended to `work`; T itself is not changed, and its unchanged subtrees are shared by the parts.
// Merging uses it, and so does view-volume culling, which merges as it traverses.
class Partitioner {
 public:
  // A part whose two children are the same leaf is that leaf, so a part holding nothing of the
  // solid is OUT at once (what view-volume culling needs to skip a side), and merging never
  // partitions, or cuts sub-hyperplanes for, what reduce() would remove.
  // Nodes below `first_node` are never partitioned (merging's first operand): the side array of
  // boxes starts there, so its size follows what is partitioned, not the whole work array.
  Partitioner(SolidTree& work, MergeStats& stats, MergeOptions options = {}, Ref first_node = 0);
  struct Parts {
    Ref plus, minus;  // T+ and T-
  };
  Parts partition(Ref t, std::uint32_t shp_h, const Plane& h);
  // Nodes from `first_moved` on were renumbered (compaction.h): their boxes are recomputed on demand.
  void forget_boxes_from(Ref first_moved);

 private:
  // One pending partitionTree(T, shp(t1)): Pending until classified, then waiting for the parts of
  // the subtrees it descended into.
  enum class Kind : std::uint8_t { Pending, InFront, InBack, InBoth };
  struct PartFrame {
    Ref t;
    std::uint32_t shp_h;  // shp(t1) inside r(T)
    Kind kind;
    bool prune;  // false below a subtree whose walk the tolerance stopped: every box below is
                 // on the same side, and each would stop the same way
  };
  void partition_descend(std::size_t top, const Plane& h);
  // Where the box of subtree t's sub-hyperplanes lies against h: +1 farther than plane_eps in
  // front, -1 behind, 0 otherwise (or when pruning is off).
  int bounds_side(Ref t, const Plane& h);
  const Box& subtree_box(Ref t);
  // The leaf of subtree t on the side of h it has no sub-hyperplane on, reached by where shp_h lies
  // against each node's plane; kOut with ok false when a tolerance decision stops the walk (then
  // nothing is counted: the usual partition visits those nodes).
  Ref leaf_beyond(Ref t, std::uint32_t shp_h, const Plane& h, bool& ok);
  Parts partition_combine(const PartFrame& f, const Plane& h);
  bool shp_in_front(Ref t, const Plane& h);
  static bool collapses(Ref front, Ref back) { return is_leaf(front) && front == back; }
  Ref node(const Plane& plane, std::uint32_t shp, Ref front, Ref back);

  SolidTree& w_;
  MergeStats& stats_;
  const double eps_;
  const MergeOptions options_;
  const Ref first_node_;
  std::vector<Box> boxes_;       // node first_node_ + i at i: the box of its subtree's sub-hyperplanes
  std::vector<bool> box_known_;  // set once a box is computed (a node's subtree never changes)
  std::vector<Ref> stack_;
  std::vector<PartFrame> frames_;
  std::vector<Parts> parts_;
  std::vector<Vec3> front_, back_;
};

// A op B. Both operands must have been built in the same box (solid_box). The result is reduced.
SolidTree merge(const SolidTree& a, const SolidTree& b, SetOp op, MergeStats* stats = nullptr,
                MergeOptions options = {});
// The same with an explicit table: tests plant a wrong row and show the checks catch it.
SolidTree merge_with_table(const SolidTree& a, const SolidTree& b, const CellTable& table,
                           MergeStats* stats = nullptr, MergeOptions options = {});

// Collapses every subtree whose leaves all carry one label into that leaf, removes nodes whose
// plane no longer crosses their region (an empty sub-hyperplane: the child on the region's side
// takes their place), and stores the nodes that remain in pre-order. The solid is unchanged.
SolidTree reduce(const SolidTree& solid);

}  // namespace bsp
