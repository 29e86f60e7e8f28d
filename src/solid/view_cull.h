#pragma once
// View-volume culling by merging [Chrysanthou §5; Naylor1990]: the view volume as a solid tree
// (IN inside), intersected with the scene tree by partitionTree while the scene tree is traversed
// back to front, so the fragments of its IN parts are emitted as they are found and no merged tree
// is built. At each scene node the part of the volume inside the node's region is split by the
// node's sub-hyperplane: a side where nothing of the volume remains is skipped with the fragments on
// the plane, and a subtree whose region lies wholly inside the volume is walked without splitting.
//
// The corner test of traverse_culled.h asks whether the whole volume straddles a node's plane; this
// asks whether the volume's part inside the node's region does, so it emits a subsequence of that
// traversal's output, in the same order: the fragments it leaves out lie in regions the volume
// does not reach.
#include <cstdint>
#include <span>
#include <vector>

#include "solid/solid_tree.h"
#include "tree/traverse.h"
#include "tree/traverse_culled.h"
#include "tree/tree.h"

namespace bsp {

// The convex volume bounded by `outward` planes (each facing out of it), as a solid tree inside
// `box`: a chain whose front sides are OUT and whose last back side is IN.
SolidTree convex_volume_tree(std::span<const Plane> outward, const Box& box);

// The frustum's six bounding planes, facing out of it (near, far, left, right, bottom, top).
std::vector<Plane> frustum_planes(const Frustum& frustum);

struct MergeCullCounters {
  TraversalCounters traversal;        // nodes visited, plane evaluations, fragments emitted
  std::uint64_t partition_nodes = 0;  // nodes of the volume's tree visited by partitionTree
  std::uint64_t shp_splits = 0;       // sub-hyperplanes cut in two while partitioning
  std::uint64_t inside_nodes = 0;     // scene nodes reached with the volume covering their region
  std::uint64_t inconsistent = 0;     // as MergeStats::inconsistent
};

// Back to front from frustum.eye (strict and coarse trees alike).
std::vector<std::uint32_t> merged_visibility_order(const Tree& scene, const Frustum& frustum,
                                                   MergeCullCounters* counters = nullptr);

}  // namespace bsp
