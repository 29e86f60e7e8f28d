#pragma once
// The part of a build shared by the recursive and incremental builders: the tolerance from the
// input's extent, and loading the input into the draft's FragmentStore with pooled planes.
#include <span>
#include <vector>

#include "split/fragment_store.h"
#include "tree/draft.h"
#include "tree/tree.h"

namespace bsp {

// Sets tree.bounds, tree.tol (plane_eps_relative of the input's diagonal), tree.store (texture
// coordinates kept when the input has non-zero ones) and the input counters of tree.stats; returns
// the ids of the usable input fragments in input order (slivers dropped and non-planar polygons
// fan-triangulated).
std::vector<std::uint32_t> load_input(std::span<const Polygon> input, TreeDraft& tree,
                                      double plane_eps_relative = kPlaneEpsRelative);

// The same for polygons added to a draft whose tolerance and store are already set: polygon i gets
// source first_source + i, and the input counters add to `stats` (the caller's, which need not be
// the draft's).
std::vector<std::uint32_t> add_input(std::span<const Polygon> input, std::uint32_t first_source, TreeDraft& tree,
                                     BuildStats& stats);

}  // namespace bsp
