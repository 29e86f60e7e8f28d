#include "geometry/plane.h"

#include <algorithm>
#include <bit>

namespace bsp {

namespace {

constexpr std::size_t kInitialSlots = 64;

// FNV-1a over the components' bits, with -0 read as +0 so that planes equal under == hash alike.
std::uint64_t hash(const Plane& p) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : {p.n.x, p.n.y, p.n.z, p.d}) {
    h ^= std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v);
    h *= 0x100000001b3ULL;
    h ^= h >> 29;
  }
  return h;
}

}  // namespace

std::uint32_t PlanePool::find(const Plane& p) const {
  if (slots_.empty()) return 0;
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = hash(p) & mask;; i = (i + 1) & mask) {
    const std::uint32_t s = slots_[i];
    if (s == 0 || planes_[s - 1] == p) return s;
  }
}

void PlanePool::insert(std::uint32_t pair) {
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = hash(planes_[pair]) & mask;
  while (slots_[i] != 0) i = (i + 1) & mask;
  slots_[i] = pair + 1;
}

void PlanePool::grow() {
  slots_.assign(std::max(kInitialSlots, 2 * slots_.size()), 0);
  for (std::uint32_t pair = 0; pair < planes_.size(); ++pair) insert(pair);
}

std::uint32_t PlanePool::add(const Plane& p) {
  if (const std::uint32_t s = find(p)) return 2 * (s - 1);
  if (const std::uint32_t s = find(p.flipped())) return flip(2 * (s - 1));
  const auto pair = static_cast<std::uint32_t>(planes_.size());
  planes_.push_back(p);
  if (2 * planes_.size() > slots_.size()) grow();
  else insert(pair);
  return 2 * pair;
}

}  // namespace bsp
