#pragma once
// A frozen BSP tree: nodes in one flat array linked by indices, planes in a pool, fragments in flat
// arrays grouped by the node that stores them. Built in scratch memory by build.h, never modified
// afterwards.
//
// Shapes ([AlphaBSP]):
//  - Strict: every node has a partitioning plane and stores the fragments coplanar with it
//    [Fuchs1980]. Empty cells are not stored: a missing child is kNull.
//  - Coarse: additionally, a leaf may hold several fragments once they form a convex set (each in
//    front of or on every other's plane; IS-CONVEX-SET of [DividingPolygon]). Such a leaf has plane kNull.
//  - Leafy: every fragment lives in a leaf (plane kNull) and every other node stores none; a fragment
//    in a node's plane goes to the child on the side it faces (front when its plane's normal agrees).
//    A leaf is the boundary of a convex cell: each fragment in front of every other's plane, or in it
//    facing the same way; with leaf groups (BuildOptions), also of one group. This is the tree of
//    Quake's and Doom's node builders, where a leaf (a subsector) is a convex piece of one sector.
//
// Depth convention: the root has depth 1, so a tree of n nodes has max depth >= ceil(log2(n+1)).
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "geometry/fragment_array.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/tolerance.h"

namespace bsp {

inline constexpr std::uint32_t kNull = 0xffffffffu;

enum class Shape : std::uint8_t { Strict, Coarse, Leafy };
// "strict", "coarse", "leafy": the names the CLI, the sweep and every JSON use.
const char* shape_name(Shape s);
std::optional<Shape> shape_named(std::string_view name);

// 16 bytes. Nodes are stored in pre-order (front child first) and fragments in node order, so a
// node's fragments run from its `first` to the next node's (Tree::fragments_of).
struct Node {
  std::uint32_t plane = kNull;  // pooled plane; kNull for a coarse leaf
  std::uint32_t front = kNull;  // child in the plane's front half-space
  std::uint32_t back = kNull;
  std::uint32_t first = 0;      // its first fragment in Tree::fragments

  bool is_cell_leaf() const { return plane == kNull; }
  bool has_children() const { return front != kNull || back != kNull; }
};

// Fragment indices [begin, end).
struct FragmentRange {
  std::uint32_t begin = 0, end = 0;
  std::uint32_t size() const { return end - begin; }
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
  std::uint64_t mixed_leaves = 0;     // leafy: convex leaves of several groups no plane could part
  std::uint64_t tasks = 0;            // subtrees built as separate tasks (BuildOptions::task_share)
  double build_seconds = 0.0;
  // The bill of a recursive build, wall seconds summed over the threads that did each part (so on
  // two threads the sum can reach twice build_seconds): choosing planes (inside Splitter::choose:
  // the heuristic's own work) and the build's own work (loading the input; partitioning, splitting
  // and emitting nodes in the builders; laying out the tasks' subtrees and freezing the tree).
  // Timings: they depend on the machine, never on the tree. Zero for an incremental build.
  double choose_seconds = 0.0;
  double machinery_seconds = 0.0;
  // Point-against-plane tests that classified fragments (a bounding-sphere centre, then each
  // vertex when the sphere straddles the plane), all of them and those inside choose: the unit of
  // the heuristics' and the partitioning's work, for a rate against the machine's (bench/roofline.h).
  // Deterministic. Not counted: splitting's own vertex distances and the leafy shape's convexity
  // checks (leaf_cell.h), which test points without classifying a fragment.
  std::uint64_t side_tests = 0;
  std::uint64_t choose_side_tests = 0;
};

// Where a tree's bytes go (Tree::bytes), part by part.
struct TreeBytes {
  std::size_t positions = 0;   // fragment vertices: 24 bytes each (three doubles)
  std::size_t attributes = 0;  // texture coordinates: 8 bytes per vertex, only when the input has any
  std::size_t fragments = 0;   // per fragment: its vertex offset, source and supporting plane
  std::size_t nodes = 0;
  std::size_t planes = 0;  // the pooled planes
  std::size_t total() const { return positions + attributes + fragments + nodes + planes; }
};

// Built in scratch memory (tree/draft.h) and frozen; never modified afterwards. Traversal reads
// nodes, planes and fragment_plane; vertices are read only by queries that need the geometry.
struct Tree {
  std::vector<Node> nodes;  // nodes[0] is the root; empty for an empty input
  PlanePool planes;
  FragmentArray fragments;
  std::vector<std::uint32_t> fragment_plane;  // parallel to fragments: each one's supporting plane
  Shape shape = Shape::Strict;
  Tolerance tol;
  Box bounds;  // the input's bounding box
  BuildStats stats;

  bool empty() const { return nodes.empty(); }
  FragmentRange fragments_of(std::uint32_t node) const {
    const auto end = node + 1 < nodes.size() ? nodes[node + 1].first : static_cast<std::uint32_t>(fragments.size());
    return {nodes[node].first, end};
  }
  // The bytes of what the tree stores, the plane pool included (sizes, not capacities), so the
  // count is the same with any standard library's growth policy and can be compared exactly.
  std::size_t bytes() const { return bytes_by_part().total(); }
  TreeBytes bytes_by_part() const;
};

}  // namespace bsp
