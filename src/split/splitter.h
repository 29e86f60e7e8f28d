#pragma once
// The splitter interface: the build loop (tree/build.cpp) asks a Splitter for a node's plane and
// does everything else itself (partitioning, node creation, the fallback when a plane separates
// nothing). One heuristic per file in src/split/, registered by name in registry.cpp.
#include <cstdint>
#include <memory>
#include <span>

#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "split/fragment_store.h"

namespace bsp {

// What a splitter may look at when choosing the plane of one node.
struct SplitContext {
  std::span<const std::uint32_t> ids;  // the node's fragments, in a deterministic order
  const FragmentStore& frags;
  const PlanePool& planes;
  Tolerance tol;
  Box scene_box;  // bounding box of the whole input
  // The node's cell: scene_box (enlarged by the splitter's own margin if it needs a bounded cell)
  // intersected with the front half-space of each of these pooled planes, root first.
  std::span<const std::uint32_t> cell_planes;
  std::uint32_t depth = 1;  // of the node being made; the root has depth 1
};

struct SplitChoice {
  enum class Kind : std::uint8_t { None, Fragment, Free };
  Kind kind = Kind::None;
  std::uint32_t fragment = 0;  // Kind::Fragment: use this fragment's pooled plane (an autopartition)
  Plane plane;                 // Kind::Free: a plane through no particular fragment

  static SplitChoice none() { return {}; }
  static SplitChoice of_fragment(std::uint32_t id) { return {Kind::Fragment, id, {}}; }
  static SplitChoice free_plane(const Plane& p) { return {Kind::Free, 0, p}; }
};

class Splitter {
 public:
  virtual ~Splitter() = default;
  // Called once per node with at least one fragment, in a deterministic order, so stateful
  // splitters (seeded sampling) give the same tree on every run. Kind::None leaves the choice to
  // the build loop's fallback.
  virtual SplitChoice choose(const SplitContext& ctx) = 0;
  // Whether choose() reads ctx.cell_planes; computing them costs O(depth) per node.
  virtual bool needs_cell() const { return false; }
};

}  // namespace bsp
