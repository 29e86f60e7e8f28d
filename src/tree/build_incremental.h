#pragma once
// Incremental construction (Thibault and Naylor [Thibault1987]): polygons are inserted one at a time,
// split on their way down, and each one that reaches an empty cell makes a node with its plane.
//
// Coarse shape: a polygon reaching a coarse leaf joins it while the leaf stays a convex set;
// otherwise the leaf becomes a node on the newcomer's plane and its old fragments, which are a
// convex set and so stay one on either side, become the node's two leaves (or its coplanar set).
//
// The insertion order replaces the splitter: the first polygon to reach a cell picks its plane.
// The splitter argument is accepted for a uniform build interface and not consulted.
#include <vector>

#include "split/fragment_store.h"
#include "split/splitter.h"
#include "tree/build_options.h"
#include "tree/draft.h"

namespace bsp {

void build_incremental(TreeDraft& tree, std::vector<std::uint32_t> ids, Splitter& splitter,
                       const BuildOptions& options);

}  // namespace bsp
