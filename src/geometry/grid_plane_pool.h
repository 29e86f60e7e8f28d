#pragma once
// The exact kernel's ± plane pool, as PlanePool (geometry/plane.h; ericw-tools qbsp/map.cc): index
// 2k is a grid plane in canonical form (geometry/grid_plane.h), 2k + 1 its opposite, so
// orientation is the low bit and two pooled planes are the same plane exactly when their indices
// are equal up to that bit. Canonical coefficients make that exact: planes that are the same set
// of points share an index whatever three points they were made from.
//
// Beside each plane the pool keeps what the rest of the suite reads in doubles, at the same
// indices: its coefficients rounded for the predicates' filter (PlaneApprox), and its unit-normal
// form in scene coordinates (a PlanePool), for splitters' estimates and for output. Neither decides
// a side.
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/exact_predicates.h"
#include "geometry/grid.h"
#include "geometry/grid_plane.h"
#include "geometry/plane.h"

namespace bsp {

// The unit-normal plane of scene coordinates nearest a grid plane (rounded in doubles: an estimate).
Plane scene_plane(const GridPlane& p, const Grid& grid);
// The same from the plane's rounded coefficients (approximate(p)), which round alike.
Plane scene_plane(const PlaneApprox& p, const Grid& grid);

class GridPlanePool {
 public:
  explicit GridPlanePool(const Grid& grid) : grid_(grid) {}

  // The index of `p` (made canonical) in its own orientation, added when new.
  std::uint32_t add(const GridPlane& p);
  // Room for this many pairs without rehashing.
  void reserve(std::size_t pairs);
  GridPlane operator[](std::uint32_t i) const { return (i & 1u) ? -planes_[i >> 1] : planes_[i >> 1]; }
  PlaneApprox approx(std::uint32_t i) const {
    const PlaneApprox& a = approx_[i >> 1];
    return (i & 1u) ? PlaneApprox{-a.a, -a.b, -a.c, -a.d} : a;
  }
  // The scene planes, index for index.
  const PlanePool& scene_planes() const { return scene_; }
  const Grid& grid() const { return grid_; }
  std::size_t size() const { return 2 * planes_.size(); }
  // The planes by pair (pair k is index 2k), given away: the pool is not read afterwards.
  std::vector<GridPlane> release_planes() { return std::move(planes_); }

 private:
  // The slot of `key` in index_, or the empty slot where it belongs (linear probing).
  std::size_t slot(const GridPlane& key) const;
  // Doubles index_ and reinserts every pair, in index order (deterministic).
  void grow_index(std::size_t slots);

  Grid grid_;
  std::vector<GridPlane> planes_;  // canonical, the orientation whose first nonzero coefficient is positive
  std::vector<PlaneApprox> approx_;
  PlanePool scene_;  // appended in step with planes_, never looked up (two grid planes may round alike)
  // Open addressing over planes_: pair + 1 per slot, 0 empty; a power-of-two size, at most half
  // full. No node per plane (an unordered_map allocates one), one probe most of the time.
  std::vector<std::uint32_t> index_;
};

}  // namespace bsp
