#include "geometry/grid_plane_pool.h"

#include <cmath>

namespace bsp {

namespace {

// The orientation of a canonical plane the pool stores: its first nonzero coefficient positive.
bool stored_orientation(const GridPlane& p) {
  for (Int128 v : {p.a, p.b, p.c, p.d})
    if (v != 0) return v > 0;
  return true;
}

}  // namespace

Plane scene_plane(const GridPlane& p, const Grid& grid) {
  // a . (x - origin) / step + d = 0, multiplied by step / |a|.
  const Vec3 a{static_cast<double>(p.a), static_cast<double>(p.b), static_cast<double>(p.c)};
  const double length = std::sqrt(dot(a, a));
  const Vec3 n = a / length;
  return {n, (static_cast<double>(p.d) * grid.step() - dot(a, grid.origin())) / length};
}

std::size_t GridPlanePool::Hash::operator()(const GridPlane& p) const {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (Int128 v : {p.a, p.b, p.c, p.d})
    for (std::uint64_t half : {static_cast<std::uint64_t>(v), static_cast<std::uint64_t>(v >> 64)}) {
      h ^= half;
      h *= 0x100000001b3ULL;
      h ^= h >> 29;
    }
  return h;
}

void GridPlanePool::reserve(std::size_t pairs) {
  planes_.reserve(pairs);
  approx_.reserve(pairs);
  scene_.reserve(pairs);
  index_.reserve(pairs);
}

std::uint32_t GridPlanePool::add(const GridPlane& p) {
  const GridPlane c = canonical(p);
  const bool as_stored = stored_orientation(c);
  const GridPlane key = as_stored ? c : -c;
  const auto [it, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(planes_.size()));
  if (inserted) {
    planes_.push_back(key);
    approx_.push_back(approximate(key));
    scene_.append_distinct(scene_plane(key, grid_));
  }
  return 2 * it->second + (as_stored ? 0u : 1u);
}

}  // namespace bsp
