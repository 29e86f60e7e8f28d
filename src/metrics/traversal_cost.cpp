#include "metrics/traversal_cost.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bsp {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Up falls back to +x when |look.z| exceeds this (look within ~8° of the z axis).
constexpr double kUpParallelLimit = 0.99;

Vec3 fibonacci_direction(std::uint32_t k, std::uint32_t count) {
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * k + 1.0) / count;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = golden_angle * k;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Frustum view(const Box& box, const Vec3& u, bool outside) {
  const Vec3 c = box.center();
  const double d = std::max(box.diagonal(), 1e-300);
  Frustum f;
  if (outside) {
    f = {c + u * d, -u, {}, 60 * kDegree, 45 * kDegree, 0.01 * d, 2 * d};
  } else {
    const Vec3 s = box.size() * 0.25;
    f = {c + Vec3{s.x * u.x, s.y * u.y, s.z * u.z}, u, {}, 90 * kDegree, 60 * kDegree, 0.001 * d, d};
  }
  f.up = std::abs(f.look.z) > kUpParallelLimit ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  return f;
}

}  // namespace

std::vector<Frustum> metric_views(const Box& box, std::uint32_t count) {
  std::vector<Frustum> out;
  for (std::uint32_t k = 0; k < count; ++k) out.push_back(view(box, fibonacci_direction(k, count), k % 2 == 0));
  return out;
}

TraversalCost traversal_cost(const Tree& tree, std::span<const Frustum> views) {
  TraversalCost out;
  if (views.empty() || tree.empty()) return out;
  std::vector<std::uint32_t> order;  // one list for every view: only the counters are kept
  for (const Frustum& f : views) {
    const TraversalCounters full = visibility_order(tree, f.eye, Order::BackToFront, order);
    const TraversalCounters culled = traverse_culled(tree, f, [](std::uint32_t) {});
    out.full_nodes_visited += static_cast<double>(full.nodes_visited);
    out.full_plane_evals += static_cast<double>(full.plane_evals);
    out.culled_nodes_visited += static_cast<double>(culled.nodes_visited);
    out.culled_plane_evals += static_cast<double>(culled.plane_evals);
    out.culled_fragments_emitted += static_cast<double>(culled.fragments_emitted);
  }
  const auto n = static_cast<double>(views.size());
  out.full_nodes_visited /= n;
  out.full_plane_evals /= n;
  out.culled_nodes_visited /= n;
  out.culled_plane_evals /= n;
  out.culled_fragments_emitted /= n;
  return out;
}

}  // namespace bsp
