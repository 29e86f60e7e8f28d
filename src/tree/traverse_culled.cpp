#include "tree/traverse_culled.h"

#include <cmath>

namespace bsp {

namespace {

struct ViewAxes {
  Vec3 look, right, up;
};

ViewAxes axes(const Frustum& f) {
  const Vec3 look = normalize(f.look);
  const Vec3 right = normalize(cross(look, f.up));
  return {look, right, cross(right, look)};
}

}  // namespace

std::array<Vec3, 8> Frustum::corners() const {
  const ViewAxes a = axes(*this);
  const double tx = std::tan(fov_x / 2), ty = std::tan(fov_y / 2);
  std::array<Vec3, 8> out;
  int k = 0;
  for (double z : {near, far})
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) out[k++] = eye + a.look * z + a.right * (sx * z * tx) + a.up * (sy * z * ty);
  return out;
}

bool Frustum::contains(const Vec3& p, double margin) const {
  const ViewAxes a = axes(*this);
  const Vec3 q = p - eye;
  const double z = dot(q, a.look);
  if (z < near + margin || z > far - margin) return false;
  // Distance to a side plane through the eye is (z tan(fov/2) - |offset|) cos(fov/2).
  const double cx = std::cos(fov_x / 2), cy = std::cos(fov_y / 2);
  return (z * std::tan(fov_x / 2) - std::abs(dot(q, a.right))) * cx >= margin &&
         (z * std::tan(fov_y / 2) - std::abs(dot(q, a.up))) * cy >= margin;
}

namespace detail {

Visit frustum_side(const Plane& plane, const std::array<Vec3, 8>& corners, double eps, std::uint64_t& evals) {
  bool front = true, back = true;  // every corner tested so far is strictly in front / behind
  for (const Vec3& p : corners) {
    ++evals;
    const double d = plane.distance(p);
    front &= d > eps;
    back &= d < -eps;
    if (!front && !back) return Visit::Both;
  }
  return front ? Visit::FrontOnly : Visit::BackOnly;
}

}  // namespace detail

std::vector<std::uint32_t> culled_visibility_order(const Tree& tree, const Frustum& frustum,
                                                   TraversalCounters* counters) {
  std::vector<std::uint32_t> out;
  const TraversalCounters c = traverse_culled(tree, frustum, [&](std::uint32_t i) { out.push_back(i); });
  if (counters) *counters = c;
  return out;
}

}  // namespace bsp
