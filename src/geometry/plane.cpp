#include "geometry/plane.h"

#include <bit>
#include <functional>

namespace bsp {

std::size_t PlanePool::KeyHash::operator()(const Key& k) const {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : {k.a, k.b, k.c, k.d}) {
    h ^= std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v);
    h *= 0x100000001b3ULL;
    h ^= h >> 29;
  }
  return static_cast<std::size_t>(h);
}

std::uint32_t PlanePool::add(const Plane& p) {
  const Key key{p.n.x, p.n.y, p.n.z, p.d};
  if (auto it = index_.find(key); it != index_.end()) return it->second;
  const Key flipped{-p.n.x, -p.n.y, -p.n.z, -p.d};
  if (auto it = index_.find(flipped); it != index_.end()) return flip(it->second);
  const auto i = static_cast<std::uint32_t>(2 * planes_.size());
  planes_.push_back(p);
  index_.emplace(key, i);
  return i;
}

}  // namespace bsp
