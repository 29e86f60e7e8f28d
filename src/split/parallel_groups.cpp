#include "split/parallel_groups.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace bsp {

namespace {

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

class Grid {
 public:
  explicit Grid(double cell) : cell_(cell) {}

  Cell cell_of(const Vec3& v) const {
    return {static_cast<std::int64_t>(std::floor(v.x / cell_)), static_cast<std::int64_t>(std::floor(v.y / cell_)),
            static_cast<std::int64_t>(std::floor(v.z / cell_))};
  }
  void insert(const Vec3& v, std::uint32_t group) { cells_[cell_of(v)].push_back(group); }

  // Calls f(group) for every group stored in the 27 cells around v's: all within one cell width.
  template <class F>
  void around(const Vec3& v, F f) const {
    const Cell c = cell_of(v);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it != cells_.end())
            for (auto g : it->second) f(g);
        }
  }

 private:
  double cell_;
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> cells_;
};

constexpr std::uint32_t kNoGroup = 0xffffffffu;

}  // namespace

ParallelGroups group_parallel(std::span<const Vec3> normals, double angle) {
  // Unit vectors at most `angle` apart are at most this chord apart, so in neighbouring cells.
  const double chord = 2.0 * std::sin(angle / 2.0);
  const double chord2 = chord * chord;
  Grid grid(chord);
  ParallelGroups out;
  out.group_of.reserve(normals.size());
  for (const Vec3& n : normals) {
    std::uint32_t found = kNoGroup;
    const auto consider = [&](std::uint32_t g) {
      // Compared as chords rather than cosines: cos(angle) rounds to 1 for tiny angles.
      const Vec3& r = out.representative[g];
      const Vec3 a = n - r, b = n + r;
      if (g < found && std::min(dot(a, a), dot(b, b)) <= chord2) found = g;
    };
    grid.around(n, consider);
    grid.around(-n, consider);
    if (found == kNoGroup) {
      found = static_cast<std::uint32_t>(out.size.size());
      out.size.push_back(0);
      out.representative.push_back(n);
      grid.insert(n, found);
    }
    ++out.size[found];
    out.group_of.push_back(found);
  }
  return out;
}

}  // namespace bsp
