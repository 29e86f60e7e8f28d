#pragma once
// The tree the dynamic strategies edit frame by frame: nodes linked by indices in one array (freed
// slots reused), each with its fragment list, over one fragment store and plane pool. A frame's
// frozen Tree (tree/tree.h) is a snapshot of it, taken outside the timed update.
//
// Notation: an owner is who put fragments or planes in the tree: owner 0 the static polygons,
// owner k + 1 moving object k. A fragment's source is its polygon's index in the frame's input
// (the static polygons, then the moving ones object by object), so its owner follows from its
// source and survives splits, and a snapshot is checked against the frame's input like any tree.
// A node's owner is the owner whose fragments or separating plane made it.
//
// Invariants between updates: the tree is a valid strict BSP tree of the live fragments (every
// fragment in its node's plane, every subtree on its side of each ancestor); a node without
// fragments is a free plane of a build or a separating plane (torres), owned by whoever made it and
// removed with it; per owner, live fragments = input polygons kept + splits - dropped slivers
// (BuildStats' identity), which the snapshot's invariant check verifies.
//
// Memory: the plane pool only grows. Every plane a frame adds (moved fragments, object trees moved
// to their poses) stays in it, 32 bytes each, so a long run's pool outgrows its live planes.
#include <cstdint>
#include <span>
#include <vector>

#include "dynamic/update_work.h"
#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/draft.h"
#include "tree/tree.h"

namespace bsp {

inline constexpr std::uint32_t kStaticOwner = 0;
inline constexpr std::uint32_t kFreedNode = 0xffffffffu;  // DynNode::owner of a free slot

struct DynNode {
  std::uint32_t plane = kNull;
  std::uint32_t front = kNull, back = kNull, parent = kNull;
  std::uint32_t owner = kStaticOwner;
  std::vector<std::uint32_t> frags;  // ids in the store, all on `plane`
  std::uint32_t child(bool front_side) const { return front_side ? front : back; }
};

// A child link: parent's front or back, or the root when parent is kNull.
struct Slot {
  std::uint32_t parent = kNull;
  bool front = true;
};

// The box of both polygon sets: a dynamic tree's tolerance and splitter box, from the first frame.
Box bounds_of(std::span<const Polygon> a, std::span<const Polygon> b);

class DynamicTree {
 public:
  // Loads the static polygons (sources 0..) and sets the tolerance and bounds from `bounds`, which
  // must hold every frame's polygons. `moving_per_object` polygons per object, `objects` objects.
  DynamicTree(std::span<const Polygon> static_polys, std::size_t objects, std::size_t moving_per_object,
              const Box& bounds);

  // Loads object k's polygons at their new place (sources numbered by the frame layout); returns
  // their ids. Slivers are dropped and counted against the object.
  std::vector<std::uint32_t> load_object(std::uint32_t k, std::span<const Polygon> polys);
  std::vector<std::uint32_t> static_ids() const { return static_ids_; }

  // Filters fragments of one owner down from `start` (the root when kNull): coplanar ones join the
  // node, the rest split and go on; fragments reaching an empty cell are built into a subtree there
  // by `splitter`, with this tree's tolerance and the cell's planes.
  void insert(std::vector<std::uint32_t> ids, std::uint32_t owner, Splitter& splitter, UpdateWork& work,
              std::uint32_t start = kNull);
  // Builds the whole tree from the static and the given fragments as one build (a frame-0 tree).
  void build_all(std::vector<std::uint32_t> ids, Splitter& splitter, UpdateWork& work);

  // Removes every fragment of `owner` and every node it made that is left with no fragments:
  // bottom-up; a node with one non-empty subtree is replaced by it, one with two is repaired
  // (UpdateWork::repairs) with `splitter` building the reinserted fragments' new cells.
  // Several owners at once: all their fragments first, then their nodes, so a node of one above a
  // node of another is not repaired for fragments about to go.
  void remove(std::span<const std::uint32_t> owners, Splitter& splitter, UpdateWork& work);
  // A part of an object tree built elsewhere (dynamic/object_tree.h): a fragment with its source
  // already set, and the input counters of the object's build (its polygons, splits and drops).
  std::uint32_t add_fragment(const Polygon& poly, std::uint32_t plane);
  void count_input(std::uint32_t owner, const BuildStats& built);
  std::uint32_t owner_of_source(std::uint32_t source) const;
  std::uint32_t source_base(std::uint32_t k) const { return static_cast<std::uint32_t>(static_count_ + k * per_object_); }
  // The owners whose nodes repairs dismantled since the last call (their fragments now sit in nodes
  // the repair built), each once.
  std::vector<std::uint32_t> take_disturbed();

  // Hanging prebuilt parts (merge and torres): a new node on `plane` owned by `owner`, linked at
  // `slot` (which must be empty); its fragments are added with add_fragments.
  std::uint32_t add_node(Slot slot, std::uint32_t plane, std::uint32_t owner);
  void add_fragments(std::uint32_t node, std::span<const std::uint32_t> ids);
  // Puts a new node on `plane` in place of `node`, with `node` as its child on `node_side`.
  std::uint32_t insert_above(std::uint32_t node, std::uint32_t plane, std::uint32_t owner, bool node_side);
  Slot slot_of(std::uint32_t node) const;
  std::uint32_t child_at(Slot slot) const { return slot.parent == kNull ? root_ : nodes_[slot.parent].child(slot.front); }
  // Counts a split of one of owner's fragments (callers that split with store() directly).
  void count_split(std::uint32_t owner, const FragmentStore::Parts& parts);

  // The frozen tree of the current state: nodes in pre-order, the frame's input counters in stats.
  Tree snapshot() const;

  std::uint32_t owner_of_fragment(std::uint32_t id) const;
  std::uint32_t root() const { return root_; }
  const DynNode& node(std::uint32_t n) const { return nodes_[n]; }
  DynNode& node(std::uint32_t n) { return nodes_[n]; }
  FragmentStore& store() { return draft_.store; }
  const FragmentStore& store() const { return draft_.store; }
  PlanePool& planes() { return draft_.planes; }
  const PlanePool& planes() const { return draft_.planes; }
  const Tolerance& tol() const { return draft_.tol; }
  const Box& bounds() const { return draft_.bounds; }
  // The nodes `owner` made that are still its own (stale entries filtered).
  std::vector<std::uint32_t> owned_nodes(std::uint32_t owner) const;

 private:
  struct Pending {
    std::uint32_t node;
    std::vector<std::uint32_t> ids;
  };
  void filter(std::uint32_t n, std::vector<std::uint32_t>& ids, std::uint32_t owner, std::vector<Pending>& stack,
              Splitter& splitter, UpdateWork& work);
  void build_at(Slot slot, std::vector<std::uint32_t> ids, std::uint32_t owner, Splitter& splitter, UpdateWork& work);
  std::vector<std::uint32_t> cell_planes(Slot slot) const;
  std::uint32_t depth_of(std::uint32_t n) const;
  std::uint64_t path_key(Slot slot) const;
  std::uint32_t new_node(std::uint32_t plane, std::uint32_t owner, std::uint32_t parent);
  void free_node(std::uint32_t n);
  void link(Slot slot, std::uint32_t child);
  void remove_fragments(std::uint32_t owner, UpdateWork& work);
  void collect_dead(std::uint32_t owner, std::vector<std::pair<std::uint32_t, std::uint32_t>>& dead);
  void remove_dead(std::uint32_t n, Splitter& splitter, UpdateWork& work);
  std::uint64_t subtree_size(std::uint32_t n) const;
  std::vector<std::uint32_t> dismantle(std::uint32_t n, UpdateWork& work);

  TreeDraft draft_;  // store, planes, tolerance and bounds; nodes and fragments only while building
  std::vector<DynNode> nodes_;
  std::vector<std::uint32_t> free_;
  std::uint32_t root_ = kNull;
  std::size_t static_count_ = 0, per_object_ = 0;
  std::vector<std::uint32_t> static_ids_;
  std::vector<BuildStats> counters_;                     // per owner: input counters, splits, drops
  std::vector<std::vector<std::uint32_t>> holds_;        // per owner: nodes that got its fragments
  std::vector<std::vector<std::uint32_t>> made_;         // per owner: nodes it made
  std::vector<std::uint32_t> disturbed_;
};

}  // namespace bsp
