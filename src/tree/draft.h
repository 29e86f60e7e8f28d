#pragma once
// A tree while it is being built: nodes carry their fragment counts, and fragments are ids in the
// draft's own FragmentStore, where builders split and add them (or, once a build's tasks are laid
// out, in the stores the tasks built in). Every builder lays its nodes out in pre-order (front
// child first) with the fragment ids in node order; freeze() then packs the draft into a Tree.
#include <cstdint>
#include <vector>

#include "split/fragment_store.h"
#include "tree/tree.h"

namespace bsp {

struct DraftNode {
  std::uint32_t plane = kNull;
  std::uint32_t front = kNull;
  std::uint32_t back = kNull;
  std::uint32_t first = 0;  // fragments [first, first + count) of TreeDraft::fragments
  std::uint32_t count = 0;
};

struct SplitRecord {
  std::uint32_t source = 0;
  std::uint32_t dropped = 0;  // parts dropped as slivers
  double dropped_area = 0;
};

struct TreeDraft {
  PageVector<DraftNode> nodes;
  PlanePool planes;
  FragmentStore store;                       // the fragments, and during the build every pending one
  std::vector<std::uint32_t> fragments;      // ids in `store` (or task_stores), node after node
  std::vector<std::uint32_t> fragment_plane;  // parallel to `fragments`
  // The stores of subtrees built as tasks (tree/build.cpp), whose fragments stay where their task
  // made them until freeze() packs them: fragment i is an id in task_stores[fragment_store[i] - 1],
  // or in `store` when fragment_store[i] is 0 or fragment_store is empty (a build without tasks).
  std::vector<FragmentStore> task_stores;
  std::vector<std::uint32_t> fragment_store;
  Shape shape = Shape::Strict;
  Tolerance tol;
  Box bounds;
  BuildStats stats;
  // When set, every split a builder makes is logged with its fragment's source, so a caller whose
  // sources belong to groups (dynamic/dynamic_tree.h) can count splits per group. Off in plain builds.
  bool log_splits = false;
  std::vector<SplitRecord> split_log;
};

// The last step of every build. Renumbers the plane pool in the order nodes use their planes, so a
// traversal (which visits nodes near their stored order) reads the pool front to back instead of at
// random, and drops planes no node or fragment uses; orientation and sharing are kept (a node and
// a fragment on one plane still have indices equal up to the low bit). Packs the fragments into
// flat arrays in node order and releases the stores.
Tree freeze(TreeDraft&& draft);

}  // namespace bsp
