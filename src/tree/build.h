#pragma once
// Building a tree from polygons. The recursive build (seed 000 §2) runs on an explicit work stack,
// so a degenerate input that makes a chain as deep as the input is long cannot overflow the call
// stack. The result is frozen: nodes in pre-order (front child first), fragments grouped by node.
#include <cstdint>
#include <span>

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

}  // namespace bsp
