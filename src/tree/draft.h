#pragma once
// A tree while it is being built: nodes carry their fragment counts and fragments are Polygons, so
// builders can split, move and append freely. Every builder lays its nodes out in pre-order (front
// child first) with the fragments in node order; freeze() then packs the draft into a Tree.
#include <cstdint>
#include <vector>

#include "tree/tree.h"

namespace bsp {

struct DraftNode {
  std::uint32_t plane = kNull;
  std::uint32_t front = kNull;
  std::uint32_t back = kNull;
  std::uint32_t first = 0;  // fragments [first, first + count) of TreeDraft::fragments
  std::uint32_t count = 0;
};

struct TreeDraft {
  std::vector<DraftNode> nodes;
  PlanePool planes;
  std::vector<Polygon> fragments;
  std::vector<std::uint32_t> fragment_plane;
  Shape shape = Shape::Strict;
  Tolerance tol;
  Box bounds;
  BuildStats stats;
};

// The last step of every build. Renumbers the plane pool in the order nodes use their planes, so a
// traversal (which visits nodes near their stored order) reads the pool front to back instead of at
// random, and drops planes no node or fragment uses; orientation and sharing are kept (a node and
// a fragment on one plane still have indices equal up to the low bit). Packs the fragments into
// flat arrays, releasing each Polygon as it is copied so the two forms are not both whole at once.
Tree freeze(TreeDraft&& draft);

}  // namespace bsp
