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

Plane scene_plane(const GridPlane& p, const Grid& grid) { return scene_plane(approximate(p), grid); }

Plane scene_plane(const PlaneApprox& p, const Grid& grid) {
  // a . (x - origin) / step + d = 0, multiplied by step / |a|.
  const Vec3 a{p.a, p.b, p.c};
  const double length = std::sqrt(dot(a, a));
  const Vec3 n = a / length;
  return {n, (p.d * grid.step() - dot(a, grid.origin())) / length};
}

namespace {

// The 64-bit halves of the coefficients mixed by multiplication (odd constants) and a final
// xor-shift; the slot is the low bits of the result, which depend only on each half's bits below
// 31 + log2(slots). Planes that differ only above those bits of a half share a probe sequence:
// lookups get slower, never wrong (equality decides).
std::uint64_t plane_hash(const GridPlane& p) {
  std::uint64_t h = 0;
  for (Int128 v : {p.a, p.b, p.c, p.d}) {
    h = (h ^ static_cast<std::uint64_t>(v)) * 0x9e3779b97f4a7c15ULL;
    h = (h ^ static_cast<std::uint64_t>(v >> 64)) * 0xc2b2ae3d27d4eb4fULL;
  }
  return h ^ (h >> 31);
}

}  // namespace

std::size_t GridPlanePool::slot(const GridPlane& key) const {
  const std::size_t mask = index_.size() - 1;
  for (std::size_t i = plane_hash(key) & mask;; i = (i + 1) & mask)
    if (index_[i] == 0 || planes_[index_[i] - 1] == key) return i;
}

void GridPlanePool::grow_index(std::size_t slots) {
  std::size_t size = 16;
  while (size < slots) size *= 2;
  index_.assign(size, 0);
  for (std::size_t k = 0; k < planes_.size(); ++k) index_[slot(planes_[k])] = static_cast<std::uint32_t>(k + 1);
}

void GridPlanePool::reserve(std::size_t pairs) {
  planes_.reserve(pairs);
  approx_.reserve(pairs);
  scene_.reserve(pairs);
  if (index_.size() < 2 * pairs) grow_index(2 * pairs);
}

std::uint32_t GridPlanePool::add(const GridPlane& p) {
  const GridPlane c = canonical(p);
  const bool as_stored = stored_orientation(c);
  const GridPlane key = as_stored ? c : -c;
  if (2 * (planes_.size() + 1) > index_.size()) grow_index(4 * (planes_.size() + 1));
  const std::size_t i = slot(key);
  if (index_[i] == 0) {
    planes_.push_back(key);
    approx_.push_back(approximate(key));
    scene_.append_distinct(scene_plane(approx_.back(), grid_));
    index_[i] = static_cast<std::uint32_t>(planes_.size());
  }
  return 2 * (index_[i] - 1) + (as_stored ? 0u : 1u);
}

}  // namespace bsp
