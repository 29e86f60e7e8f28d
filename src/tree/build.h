#pragma once
// Building a tree from polygons. The recursive build [Fuchs1980] runs on an explicit work stack,
// so a degenerate input that makes a chain as deep as the input is long cannot overflow the call
// stack. The result is frozen: nodes in pre-order (front child first), fragments grouped by node.
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/draft.h"
#include "tree/tree.h"

namespace bsp {

enum class InsertOrder : std::uint8_t { Given, Shuffled };

struct BuildOptions {
  Shape shape = Shape::Strict;
  bool incremental = false;                 // Thibault–Naylor insertion, one polygon at a time
  InsertOrder order = InsertOrder::Given;   // incremental only
  std::uint64_t order_seed = 0;             // InsertOrder::Shuffled only
  // How the recursive build divides its work among threads. The main builder makes the top of the
  // tree and hands every pending subtree of at most 1/task_share of the input, and at least
  // min_task_fragments fragments, to a task that builds it alone on any thread (OpenMP tasks). The
  // tree does not depend on these (tests build with other values and compare bit for bit), only how
  // the work divides: 64 leaves tens of tasks to balance two threads over; 512 keeps a task's setup
  // (moving its fragments out) small beside its work, so inputs under 32,768 polygons build on one
  // thread.
  std::size_t task_share = 64;
  std::size_t min_task_fragments = 512;
  // Shape::Leafy only: the group of each input polygon (by source index), such as a Doom seg's
  // sector; a leaf then holds fragments of one group. Empty: no groups.
  std::vector<std::uint32_t> leaf_groups{};
  // When set, every free plane (a splitter's Kind::Free choice, or the plane that parts a leafy
  // convex set of several groups) passes through it before use: a format that can only store
  // some planes (Doom's partition lines through integer points) gets the plane it will store, and
  // the tree is built with exactly that plane.
  std::function<Plane(const Plane&)> snap_free_plane{};
};

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
