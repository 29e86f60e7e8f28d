#pragma once
// Ray-shooting cost: the work of tree/ray_shoot.h over a seeded set of rays.
#include <cstdint>
#include <span>
#include <vector>

#include "tree/ray_shoot.h"

namespace bsp {

// `count` rays with origins uniform in the box and directions uniform on the unit sphere
// (Archimedes: z uniform in [-1, 1], longitude uniform), drawn from bsp::Rng streams of `seed`.
std::vector<Ray> metric_rays(const Box& box, std::uint32_t count, std::uint64_t seed);

// Means per ray (0 for no rays). With m nodes and depth h: nodes visited is at best about h (the
// first cell along the ray holds a hit) and at worst m (a ray missing everything crosses every
// cell); fragment tests at best 1, at worst every fragment.
struct RayCost {
  double nodes_visited = 0;
  double fragment_tests = 0;
  double hit_fraction = 0;              // share of rays that hit a fragment
  std::uint32_t max_nodes_visited = 0;  // over the rays
  // Point location from the rays' origins: plane tests walking from the root to the cell holding
  // the origin (a point on a plane goes front). The measured counterpart of E_point
  // (expected_cost.h), whose points are uniform in the slightly larger root cell: best about
  // log2(m + 1), worst about m.
  double point_plane_tests = 0;
};

RayCost ray_cost(const Tree& tree, std::span<const Ray> rays);
// Plane tests to locate p (0 for an empty tree).
std::uint32_t point_plane_tests(const Tree& tree, const Vec3& p);

}  // namespace bsp
