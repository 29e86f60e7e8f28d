#include "geometry/plane.h"

#include <bit>

namespace bsp {

namespace {

constexpr std::size_t kInitialSlots = 64;

// FNV-1a over the components' bits, with -0 read as +0 so that planes equal under == hash alike.
std::uint64_t oriented_hash(const Plane& p) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : {p.n.x, p.n.y, p.n.z, p.d}) {
    h ^= std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v);
    h *= 0x100000001b3ULL;
    h ^= h >> 29;
  }
  return h;
}

constexpr std::uint64_t tag_of(std::uint64_t hash) { return hash >> 32; }

}  // namespace

std::uint64_t PlanePool::hash(const Plane& p) { return oriented_hash(p) + oriented_hash(p.flipped()); }

std::uint32_t PlanePool::find(const Plane& p, std::uint64_t hash) const {
  if (slots_.empty()) return kNotFound;
  const std::size_t mask = slots_.size() - 1;
  const Plane q = p.flipped();
  for (std::size_t i = hash & mask;; i = (i + 1) & mask) {
    const std::uint64_t s = slots_[i];
    if (s == 0) return kNotFound;
    if ((s >> 32) != tag_of(hash)) continue;
    const auto pair = static_cast<std::uint32_t>(s) - 1;
    if (planes_[pair] == p) return 2 * pair;
    if (planes_[pair] == q) return 2 * pair + 1;
  }
}

void PlanePool::insert(std::uint32_t pair, std::uint64_t hash) {
  const std::size_t mask = slots_.size() - 1;
  std::size_t i = hash & mask;
  while (slots_[i] != 0) i = (i + 1) & mask;
  slots_[i] = (tag_of(hash) << 32) | (pair + 1);
}

void PlanePool::rehash(std::size_t pairs) {
  std::size_t n = kInitialSlots;
  while (n < 2 * pairs) n *= 2;
  slots_.assign(n, 0);
  for (std::uint32_t pair = 0; pair < planes_.size(); ++pair) insert(pair, hash(planes_[pair]));
  indexed_ = planes_.size();
}

void PlanePool::reserve(std::size_t pairs) {
  planes_.reserve(pairs);
  if (slots_.size() < 2 * pairs) rehash(pairs);
}

std::uint32_t PlanePool::add(const Plane& p, std::uint64_t hash) {
  if (indexed_ < planes_.size()) rehash(planes_.size());
  if (const std::uint32_t i = find(p, hash); i != kNotFound) return i;
  const auto pair = static_cast<std::uint32_t>(planes_.size());
  planes_.push_back(p);
  if (2 * planes_.size() > slots_.size()) {
    rehash(2 * planes_.size());
  } else {
    insert(pair, hash);
    indexed_ = planes_.size();
  }
  return 2 * pair;
}

std::uint32_t PlanePool::append_distinct(const Plane& p) {
  planes_.push_back(p);
  return static_cast<std::uint32_t>(2 * (planes_.size() - 1));
}

}  // namespace bsp
