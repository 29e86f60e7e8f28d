#include "metrics/ray_cost.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/rng.h"

namespace bsp {

namespace {

// Stream index of the metric's rays within `seed` (rng.h stream_seed).
constexpr std::uint64_t kRayStream = 0x4a75;

}  // namespace

std::vector<Ray> metric_rays(const Box& box, std::uint32_t count, std::uint64_t seed) {
  Rng rng(stream_seed(seed, kRayStream));
  std::vector<Ray> rays;
  rays.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const Vec3 o{rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y), rng.uniform(box.lo.z, box.hi.z)};
    const double z = rng.uniform(-1.0, 1.0);
    const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    rays.push_back({o, {r * std::cos(phi), r * std::sin(phi), z}});
  }
  return rays;
}

std::uint32_t point_plane_tests(const Tree& tree, const Vec3& p) {
  std::uint32_t tests = 0;
  for (std::uint32_t v = tree.nodes.empty() ? kNull : 0; v != kNull && !tree.nodes[v].is_cell_leaf();) {
    const Node& node = tree.nodes[v];
    ++tests;
    v = tree.planes[node.plane].distance(p) >= 0 ? node.front : node.back;
  }
  return tests;
}

RayCost ray_cost(const Tree& tree, std::span<const Ray> rays) {
  RayCost out;
  if (rays.empty()) return out;
  double hits = 0;
  for (const Ray& ray : rays) {
    const RayShot shot = shoot_ray(tree, ray);
    out.nodes_visited += shot.nodes_visited;
    out.fragment_tests += shot.fragment_tests;
    hits += shot.hit ? 1 : 0;
    out.max_nodes_visited = std::max(out.max_nodes_visited, shot.nodes_visited);
    out.point_plane_tests += point_plane_tests(tree, ray.origin);
  }
  const auto n = static_cast<double>(rays.size());
  out.nodes_visited /= n;
  out.fragment_tests /= n;
  out.hit_fraction = hits / n;
  out.point_plane_tests /= n;
  return out;
}

}  // namespace bsp
