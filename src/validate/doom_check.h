#pragma once
// A structural proof of a vanilla Doom BSP against its map, whoever built it (this code or an
// external node builder), from the records alone:
//  1. structure: from the root (the last node; subsector 0 when there are no nodes) every node
//     and every subsector is reached exactly once, and every child index is in range;
//  2. coverage: the subsectors' seg runs cover every seg exactly once, none is empty;
//  3. references: each seg's vertices and linedef exist, its side is 0 or 1 and the linedef has it;
//  4. separation: every seg endpoint under a node's child[0] lies on the right of the node's
//     partition or on it, under child[1] on the left or on it (on-line points may go either way:
//     see R_PointOnSide in io/doom_map.h), within `tolerance`;
//  5. leaves: a subsector's segs all face one sector, and each seg's endpoints lie on the right
//     of, or on, the line of every other seg of the subsector (the line of its linedef, exact
//     integers, rather than of its rounded endpoints), within `tolerance`.
// Violations are counted, never thrown. Cost: sum over segs of their depth, plus the sum over
// subsectors of the square of their seg count.
#include <cstddef>
#include <string>
#include <vector>

#include "io/doom_map.h"

namespace bsp {

// How far (map units) a seg endpoint may lie on the wrong side of a line. Vanilla vertices are
// integers, so a builder's split vertex is off its exact point: up to sqrt(1/2) = 0.71 units when
// rounded to the nearest integer point, up to sqrt(2) = 1.41 when truncated. Measured on the 68
// Freedoom maps, the largest wrong-side distance per map is at most 0.71 for glBSP's nodes and
// up to 1.35 for ZDBSP's; of the shipped nodes only one map exceeds 1.0 (7.6 units, a partition
// whose direction was stored as the short rounded vector (4, -2), seen 100 units away).
constexpr double kDoomSideTolerance = 1.5;

struct DoomCheckReport {
  std::size_t bad_children = 0;  // child index past the last node or subsector
  std::size_t unreachable_nodes = 0, repeated_nodes = 0;
  std::size_t unreachable_subsectors = 0, repeated_subsectors = 0;
  std::size_t bad_subsector_ranges = 0;  // seg runs past the last seg
  std::size_t empty_subsectors = 0;
  std::size_t uncovered_segs = 0, overlapping_segs = 0;  // in no subsector, in more than one
  std::size_t bad_seg_vertices = 0, bad_seg_linedefs = 0, bad_seg_sides = 0;
  std::size_t degenerate_partitions = 0;  // dx = dy = 0
  std::size_t wrong_side_segs = 0;        // segs with an endpoint beyond the tolerance on an ancestor's wrong side
  std::size_t non_convex_segs = 0;        // segs with an endpoint beyond the tolerance behind another seg's line
  std::size_t mixed_sector_subsectors = 0;
  // The largest distances found on the wrong side, whether within the tolerance or not.
  double worst_side_distance = 0.0;
  double worst_convexity_distance = 0.0;
  std::vector<std::string> first_problems;  // up to 10, for messages

  std::size_t violations() const;
  bool ok() const { return violations() == 0; }
};

DoomCheckReport check_doom_nodes(const DoomMap& map, const VanillaNodes& nodes, double tolerance = kDoomSideTolerance);

}  // namespace bsp
