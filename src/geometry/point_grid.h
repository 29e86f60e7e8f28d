#pragma once
// Points (or anything indexed by a point) hashed into the cubes of a uniform grid, for finding all
// entries within one cell width of a point: the 27 cells around it.
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/vec3.h"

namespace bsp {

class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}

  void insert(const Vec3& p, std::uint32_t id) { cells_[cell_of(p)].push_back(id); }

  // Calls f(id) for every id stored in the 27 cells around p's cell (so for every point within one
  // cell width of p, and some farther), cell by cell, each in insertion order.
  template <class F>
  void around(const Vec3& p, F f) const {
    const Cell c = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells_.end()) continue;
          for (std::uint32_t id : it->second) f(id);
        }
  }

  double cell() const { return cell_; }

 private:
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      const auto h = static_cast<std::size_t>(c.x) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::size_t>(c.y) * 0xc2b2ae3d27d4eb4fULL;
      return h ^ static_cast<std::size_t>(c.z) * 0x165667b19e3779f9ULL;
    }
  };
  Cell cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell_)), static_cast<std::int64_t>(std::floor(p.y / cell_)),
            static_cast<std::int64_t>(std::floor(p.z / cell_))};
  }

  double cell_;
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> cells_;
};

}  // namespace bsp
