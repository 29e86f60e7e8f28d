#pragma once
// The splitter interface: the build loop (tree/build.cpp) asks a Splitter for a node's plane and
// does everything else itself (partitioning, node creation, the fallback when a plane separates
// nothing). One heuristic per file in src/split/, registered by name in registry.cpp.
#include <cstdint>
#include <memory>
#include <span>

#include "common/rng.h"
#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "split/exact_fragments.h"
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
  // A hash of the node's path from the root (child_key). A splitter seeds any randomness it draws
  // for this node from it, so a node's choice does not depend on which nodes were built before it
  // or on which thread builds it.
  std::uint64_t node_key = kRootKey;
  // Set in an exact-kernel build (tree/exact_build.h): frags and planes are then rounded copies of
  // these exact fragments and planes, under the same ids, and SideCounter counts sides here.
  const ExactFragments* exact = nullptr;

  static constexpr std::uint64_t kRootKey = 0x6b5f0a3d2c1e9f87ULL;
  static constexpr std::uint64_t child_key(std::uint64_t parent, bool front) {
    return splitmix64(parent ^ (front ? 0x46524f4e54ULL : 0x4241434bULL));
  }
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
  // Called once per node with at least one fragment. The choice must depend only on the context
  // (randomness seeded from ctx.node_key), never on earlier calls, so that subtrees can be built
  // in any order on any thread. Kind::None leaves the choice to the build loop's fallback.
  virtual SplitChoice choose(const SplitContext& ctx) = 0;
  // An independent copy for another thread: same settings and seed, its own scratch state.
  virtual std::unique_ptr<Splitter> clone() const = 0;
  // Whether choose() reads ctx.cell_planes; computing them costs O(depth) per node.
  virtual bool needs_cell() const { return false; }
  // Throws the error the splitter met while choosing, if any. choose() and clone() run inside the
  // build's parallel regions, which no exception may leave, so a splitter that can fail (a
  // plugin's: experiments/plugin_loader.cpp) records the error, answers Kind::None from then on, and
  // the build calls this once its tree is done, outside any parallel region.
  virtual void check() const {}
};

}  // namespace bsp
