#pragma once
// A frozen BSP tree: nodes in one flat array linked by indices, planes in a pool, fragments grouped
// by the node that stores them. Built in scratch memory by build.h, never modified afterwards.
//
// Shapes ([AlphaBSP]):
//  - Strict: every node has a partitioning plane and stores the fragments coplanar with it
//    [Fuchs1980]. Empty cells are not stored: a missing child is kNull.
//  - Coarse: additionally, a leaf may hold several fragments once they form a convex set (each in
//    front of or on every other's plane; IS-CONVEX-SET of [DividingPolygon]). Such a leaf has plane kNull.
//
// Depth convention: the root has depth 1, so a tree of n nodes has max depth >= ceil(log2(n+1)).
#include <cstdint>
#include <vector>

#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/tolerance.h"

namespace bsp {

inline constexpr std::uint32_t kNull = 0xffffffffu;

enum class Shape : std::uint8_t { Strict, Coarse };

struct Node {
  std::uint32_t plane = kNull;  // pooled plane; kNull for a coarse leaf
  std::uint32_t front = kNull;  // child in the plane's front half-space
  std::uint32_t back = kNull;
  std::uint32_t first = 0;      // fragments [first, first + count) of Tree::fragments
  std::uint32_t count = 0;

  bool is_cell_leaf() const { return plane == kNull; }
  bool has_children() const { return front != kNull || back != kNull; }
};

// What the build did besides making nodes. The exact identity
//   splits = fragments - n_input + dropped_input + dropped_slivers - triangulated_extra
// holds for every tree: each split of one fragment into two adds one fragment, each drop removes
// one, and fan-triangulating a non-planar k-gon adds k - 3.
struct BuildStats {
  std::uint64_t n_input = 0;          // polygons given to the build
  std::uint64_t splits = 0;           // fragments cut in two by a partitioning plane
  std::uint64_t dropped_input = 0;    // input polygons that were already slivers (width < plane_eps)
  std::uint64_t dropped_slivers = 0;  // split parts narrower than plane_eps
  std::uint64_t triangulated_extra = 0;  // extra fragments from fan-triangulating non-planar input
  double input_area = 0.0;            // total area of the input polygons
  double dropped_area = 0.0;          // total area of everything dropped
  std::uint64_t fallbacks = 0;        // nodes where the splitter's plane separated nothing
  std::uint64_t tasks = 0;            // subtrees built as separate tasks (BuildOptions::task_share)
  double build_seconds = 0.0;
};

struct Tree {
  std::vector<Node> nodes;  // nodes[0] is the root; empty for an empty input
  PlanePool planes;
  std::vector<Polygon> fragments;
  std::vector<std::uint32_t> fragment_plane;  // parallel to fragments: each one's supporting plane
  Shape shape = Shape::Strict;
  Tolerance tol;
  Box bounds;  // the input's bounding box
  BuildStats stats;

  bool empty() const { return nodes.empty(); }
  // The last step of every build: puts the nodes in pre-order (front child first) and the fragments
  // in node order, whatever order the build made them in (subtrees built in parallel are appended
  // as they finish); then renumbers the plane pool in the order nodes use their planes, so
  // a traversal (which visits nodes in near their stored order) reads the pool front to back
  // instead of at random; planes no node or fragment uses are dropped. Orientation and sharing are
  // kept: a node and a fragment on one plane still have indices equal up to the low bit.
  void freeze();
  // The bytes of what the tree stores (sizes, not capacities), so the count is the same with any
  // standard library's growth policy and can be compared exactly.
  std::size_t bytes() const;

 private:
  void order_nodes();
};

}  // namespace bsp
