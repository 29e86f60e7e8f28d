#pragma once
// Building a tree from polygons. The recursive build [Fuchs1980] runs on an explicit work stack,
// so a degenerate input that makes a chain as deep as the input is long cannot overflow the call
// stack. The result is frozen: nodes in pre-order (front child first), fragments grouped by node.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/build_options.h"
#include "tree/draft.h"
#include "tree/tree.h"

namespace bsp {

// Input polygons must be convex; polygons that are not planar within the tolerance are
// fan-triangulated and slivers dropped (both counted in the stats). Tolerance and bounds come from
// the input's bounding box. Deterministic: same input, splitter settings and seed, same tree, bit for
// bit, on any number of threads. The splitter is cloned for each task and not itself changed.
Tree build_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options = {});
// One subtree of a tree that is edited after it is built (dynamic/): the fragments `ids` of
// draft.store, built with draft's tolerance and bounds into draft.nodes, which must be empty and
// receive the subtree in pre-order (its root first). `cell_prefix` holds the planes bounding the
// subtree's cell, root first, each oriented so the cell is in front; `depth` and `key` are the
// subtree root's depth and path key (SplitContext). Single-threaded; ids must not be empty.
void build_subtree(TreeDraft& draft, Splitter& splitter, std::vector<std::uint32_t> ids,
                   std::vector<std::uint32_t> cell_prefix, std::uint32_t depth, std::uint64_t key);

// The heuristic label of an incremental build in every JSON: it consults no heuristic.
inline constexpr std::string_view kIncrementalLabel = "incremental";

// An incremental build (options.incremental is implied): the insertion order picks every plane, so
// no splitter takes part and none is asked for.
Tree build_incremental_tree(std::span<const Polygon> input, const BuildOptions& options);

// The seed of a shuffled incremental build's insertion order in a run with `seed`; the CLI and the
// sweep derive it alike, so a sweep run's command rebuilds its tree.
std::uint64_t insertion_order_seed(std::uint64_t seed);

}  // namespace bsp
