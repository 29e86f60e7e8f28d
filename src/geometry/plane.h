#pragma once
// Oriented planes: points p with dot(n, p) + d = 0, n of unit length. The front (positive)
// half-space is where dot(n, p) + d > 0 [Chrysanthou §1].
#include <cstdint>
#include <vector>

#include "common/page_allocator.h"
#include "geometry/vec3.h"

namespace bsp {

struct Plane {
  Vec3 n;
  double d = 0;

  double distance(const Vec3& p) const { return dot(n, p) + d; }
  Plane flipped() const { return {-n, -d}; }
  bool operator==(const Plane&) const = default;

  static Plane through(const Vec3& normal, const Vec3& point) {
    const Vec3 u = normalize(normal);
    return {u, -dot(u, point)};
  }
};

// A pool of planes indexed in pairs (ericw-tools qbsp/map.cc): index 2k is a plane, 2k+1 its flip,
// so orientation is the low bit and coplanarity of two pooled planes is `(a ^ b) <= 1`. Identical
// planes (bit for bit) share an index. Only index 2k's plane is stored; the flip is negated on
// read (exactly: negation is exact), which halves the memory a traversal streams through.
class PlanePool {
 public:
  static constexpr std::uint32_t flip(std::uint32_t i) { return i ^ 1u; }
  static constexpr bool coplanar(std::uint32_t a, std::uint32_t b) { return (a ^ b) <= 1u; }
  // The pool's hash of a plane, alike for both orientations: a loader may compute it on any thread
  // ahead of add(p, hash(p)) and prefetch_slot(hash(p)).
  static std::uint64_t hash(const Plane& p);

  std::uint32_t add(const Plane& p) { return add(p, hash(p)); }
  std::uint32_t add(const Plane& p, std::uint64_t hash);  // hash must be hash(p)
  // Starts loading the table slot where add(p, hash) will begin looking.
  void prefetch_slot(std::uint64_t hash) const {
    if (!slots_.empty()) __builtin_prefetch(slots_.data() + (hash & (slots_.size() - 1)));
  }
  // Appends a plane known to be in neither orientation yet, as the next pair; returns its even index.
  // The lookup table is brought up to date by the next add(), so a pool rebuilt from distinct planes
  // (freeze, tree/draft.h) costs no hashing unless planes are added later.
  std::uint32_t append_distinct(const Plane& p);
  // Room for this many pairs without growing the table.
  void reserve(std::size_t pairs);
  Plane operator[](std::uint32_t i) const {
    const Plane& p = planes_[i >> 1];
    return (i & 1u) ? p.flipped() : p;
  }
  // Starts loading plane i into the cache, for a reader that knows which planes it will need.
  void prefetch(std::uint32_t i) const { __builtin_prefetch(planes_.data() + (i >> 1)); }
  std::size_t size() const { return 2 * planes_.size(); }  // indices, flips included
  std::size_t bytes() const { return planes_.size() * sizeof(Plane); }  // what is stored, not the capacity

 private:
  // Open addressing with linear probing over a power-of-two table kept at most half full: a lookup
  // touches one or two adjacent slots instead of a node-based map's scattered allocations, which
  // made pooling a million input planes a tenth of a build. A slot holds a pair number + 1 (0 is
  // empty) in its low half and the high half of the plane's hash in its high half, so a probe
  // passes a slot of another plane without reading that plane (a cache miss in a large pool) unless
  // their hashes agree. A plane and its flip hash alike, so one probe sequence answers for both.
  static constexpr std::uint32_t kNotFound = 0xffffffffu;
  std::uint32_t find(const Plane& p, std::uint64_t hash) const;  // p's index (either orientation), or kNotFound
  void insert(std::uint32_t pair, std::uint64_t hash);
  void rehash(std::size_t pairs);  // a table for at least this many pairs, holding every plane

  PageVector<Plane> planes_;  // page-allocated: a build drops a million-plane pool when it freezes
  PageVector<std::uint64_t> slots_;
  std::size_t indexed_ = 0;  // planes_[0, indexed_) are in slots_
};

}  // namespace bsp
