#pragma once
// Points (or anything indexed by a point) hashed into the cubes of a uniform grid, for finding all
// entries within one cell width of a point: the 27 cells around it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/vec3.h"

namespace bsp {

class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}

  void insert(const Vec3& p, std::uint32_t id) {
    Bucket& b = buckets_[find_or_add(cell_of(p))];
    const auto e = static_cast<std::uint32_t>(ids_.size());
    ids_.push_back(id);
    next_.push_back(kEnd);
    (b.head == kEnd ? b.head : next_[b.tail]) = e;
    b.tail = e;
  }

  // Calls f(id) for every id stored in the 27 cells around p's cell (so for every point within one
  // cell width of p, and some farther), cell by cell, each in insertion order.
  template <class F>
  void around(const Vec3& p, F f) const {
    const Cell c = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const std::uint32_t k = find({c.x + dx, c.y + dy, c.z + dz});
          if (k == kEnd) continue;
          for (std::uint32_t e = buckets_[k].head; e != kEnd; e = next_[e]) f(ids_[e]);
        }
  }

  // Calls f(id) for every id stored in the cells the box [lo, hi] meets (so for every point in the
  // box, and some near it), cell by cell; returns without calling f when that is more than
  // max_cells cells.
  template <class F>
  bool in_box(const Vec3& lo, const Vec3& hi, std::uint64_t max_cells, F f) const {
    const Cell a = cell_of(lo), b = cell_of(hi);
    const auto span = [](std::int64_t from, std::int64_t to) { return static_cast<std::uint64_t>(to - from + 1); };
    const std::uint64_t nx = span(a.x, b.x), ny = span(a.y, b.y), nz = span(a.z, b.z);
    // Each factor is at most max_cells before the next multiplies it: the product cannot wrap.
    if (nx > max_cells || ny > max_cells || nz > max_cells || nx * ny > max_cells || nx * ny * nz > max_cells)
      return false;
    for (std::int64_t x = a.x; x <= b.x; ++x)
      for (std::int64_t y = a.y; y <= b.y; ++y)
        for (std::int64_t z = a.z; z <= b.z; ++z) {
          const std::uint32_t k = find({x, y, z});
          if (k == kEnd) continue;
          for (std::uint32_t e = buckets_[k].head; e != kEnd; e = next_[e]) f(ids_[e]);
        }
    return true;
  }

  double cell() const { return cell_; }

 private:
  // The cells in flat arrays: a bucket per occupied cell, found through an open-addressing table
  // (linear probing, power-of-two size, at most half full) of bucket index + 1 (0 is empty), and
  // each cell's entries a list threaded through ids_ and next_ in insertion order. A node-based map
  // of heap vectors made welding a result's boundary of 10^5 faces take seconds (27 lookups a point).
  static constexpr std::uint32_t kEnd = 0xffffffffu;
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
  };
  struct Bucket {
    Cell cell;
    std::uint32_t head = kEnd, tail = kEnd;
  };
  static std::size_t hash(const Cell& c) {
    const auto h = static_cast<std::size_t>(c.x) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::size_t>(c.y) * 0xc2b2ae3d27d4eb4fULL;
    return (h ^ static_cast<std::size_t>(c.z) * 0x165667b19e3779f9ULL) * 0xff51afd7ed558ccdULL >> 17;
  }
  Cell cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell_)), static_cast<std::int64_t>(std::floor(p.y / cell_)),
            static_cast<std::int64_t>(std::floor(p.z / cell_))};
  }
  // The bucket of cell c, or kEnd.
  std::uint32_t find(const Cell& c) const {
    if (slots_.empty()) return kEnd;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = hash(c) & mask;; i = (i + 1) & mask) {
      const std::uint32_t s = slots_[i];
      if (s == 0) return kEnd;
      if (buckets_[s - 1].cell == c) return s - 1;
    }
  }
  std::uint32_t find_or_add(const Cell& c) {
    if (const std::uint32_t k = find(c); k != kEnd) return k;
    const auto k = static_cast<std::uint32_t>(buckets_.size());
    buckets_.push_back({c});
    if (2 * buckets_.size() > slots_.size()) {
      std::size_t size = 64;
      while (size < 4 * buckets_.size()) size *= 2;
      slots_.assign(size, 0);
      for (std::uint32_t b = 0; b < buckets_.size(); ++b) place(b);
    } else {
      place(k);
    }
    return k;
  }
  void place(std::uint32_t bucket) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = hash(buckets_[bucket].cell) & mask;
    while (slots_[i] != 0) i = (i + 1) & mask;
    slots_[i] = bucket + 1;
  }

  double cell_;
  std::vector<Bucket> buckets_;
  std::vector<std::uint32_t> slots_;
  std::vector<std::uint32_t> ids_, next_;  // entries: the id, and the next entry of its cell
};

}  // namespace bsp
