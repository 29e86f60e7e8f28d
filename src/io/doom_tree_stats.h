#pragma once
// The size and depth of a vanilla Doom BSP, measured from its records alone, so a tree built here
// and one written by an external node builder are measured by the same code.
#include <cstddef>
#include <cstdint>

#include "io/doom_map.h"

namespace bsp {

struct DoomTreeStats {
  std::size_t segs = 0, subsectors = 0, nodes = 0;
  // segs - the linedef sides the map has: the extra pieces splitting made. A builder that drops
  // zero-length linedefs or unreachable sides can make it negative.
  std::int64_t splits = 0;
  // Depth of a subsector in nodes from the root: 1 directly under the root, 0 when there are no
  // nodes. The mean is over subsectors reached from the root, each counted once.
  std::size_t max_depth = 0;
  double mean_depth = 0.0;
};

// Children out of range and nodes reached a second time (a cycle) are not followed.
DoomTreeStats doom_tree_stats(const DoomMap& map, const VanillaNodes& nodes);

}  // namespace bsp
