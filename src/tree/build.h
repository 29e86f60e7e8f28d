#pragma once
// Building a tree from polygons. The recursive build [Fuchs1980] runs on an explicit work stack,
// so a degenerate input that makes a chain as deep as the input is long cannot overflow the call
// stack. The result is frozen: nodes in pre-order (front child first), fragments grouped by node.
#include <cstdint>
#include <span>
#include <string_view>

#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/tree.h"

namespace bsp {

enum class InsertOrder : std::uint8_t { Given, Shuffled };

struct BuildOptions {
  Shape shape = Shape::Strict;
  bool incremental = false;                 // Thibault–Naylor insertion, one polygon at a time
  InsertOrder order = InsertOrder::Given;   // incremental only
  std::uint64_t order_seed = 0;             // InsertOrder::Shuffled only
};

// Input polygons must be convex; polygons that are not planar within the tolerance are
// fan-triangulated and slivers dropped (both counted in the stats). Tolerance and bounds come from
// the input's bounding box. Deterministic: same input, splitter state and options, same tree.
Tree build_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options = {});
// The heuristic label of an incremental build in every JSON: it consults no heuristic.
inline constexpr std::string_view kIncrementalLabel = "incremental";

// An incremental build (options.incremental is implied): the insertion order picks every plane, so
// no splitter takes part and none is asked for.
Tree build_incremental_tree(std::span<const Polygon> input, const BuildOptions& options);

// The seed of a shuffled incremental build's insertion order in a run with `seed`; the CLI and the
// sweep derive it alike, so a sweep run's command rebuilds its tree.
std::uint64_t insertion_order_seed(std::uint64_t seed);

}  // namespace bsp
