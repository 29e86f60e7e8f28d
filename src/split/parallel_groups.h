#pragma once
// Grouping plane normals by orientation: two unit normals belong together when the angle between
// them, or between one and the other's opposite, is at most a tolerance (a plane and its flip have
// the same orientation). Used by the halving-plane heuristic to find the orientation shared by the
// most polygons.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec3.h"

namespace bsp {

struct ParallelGroups {
  std::vector<std::uint32_t> group_of;  // per input normal
  std::vector<std::uint32_t> size;      // per group: how many normals joined it
  std::vector<Vec3> representative;     // per group: the normal that opened it
};

// Greedy and deterministic: normals are taken in order; each joins the lowest-numbered group whose
// representative is within `angle` radians of it or of its opposite, or opens a new group. A hash
// grid with cells as wide as the chord of `angle` finds the candidate groups, so the cost is
// O(n) expected rather than O(n · groups). Normals must have unit length; angle > 0.
ParallelGroups group_parallel(std::span<const Vec3> normals, double angle);

}  // namespace bsp
