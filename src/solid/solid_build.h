#pragma once
// A closed mesh to a solid tree: the strict build of its faces by a heuristic, then labels and
// sub-hyperplanes (solid_tree.h), each step timed.
#include <span>

#include "geometry/polygon.h"
#include "solid/solid_tree.h"
#include "split/splitter.h"
#include "tree/build.h"

namespace bsp {

struct SolidBuild {
  SolidTree solid;
  BuildStats build;           // of the strict tree
  std::uint64_t fragments = 0;
  double label_seconds = 0;   // labelling and sub-hyperplanes
  double seconds() const { return build.build_seconds + label_seconds; }
};

// Throws InputError as solid_from_tree does. options.shape is forced to Strict.
SolidBuild build_solid(std::span<const Polygon> polys, Splitter& splitter, const Box& box, BuildOptions options = {});

}  // namespace bsp
