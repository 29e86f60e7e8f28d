#pragma once
// Many plane polygons stored flat and by reference: each polygon is a run of 32-bit plane
// references (its support, then its bounds), and the planes themselves are held once, in two
// arrays: `own`, the planes as some input gave them (a polygon's support and edge planes), and
// `pooled`, a ± plane pool's planes by pair (geometry/grid_plane_pool.h). A split's parts share
// their parent's planes and the cut, so an exact build's fragments cost a few words each instead of
// a copy of every plane (64 bytes) per fragment.
//
// A reference with the top bit clear is own[r]; with it set, r & ~kPooled is a pool index: pair
// (r & ~kPooled) >> 1 of `pooled`, flipped when its low bit is set.
#include <cstdint>
#include <span>
#include <vector>

#include "common/page_allocator.h"
#include "geometry/grid_plane.h"
#include "geometry/plane_polygon.h"

namespace bsp {

class PlanePolygonSet {
 public:
  using PlaneRef = std::uint32_t;
  static constexpr PlaneRef kPooled = 0x80000000u;

  std::size_t size() const { return runs_.size(); }
  bool empty() const { return runs_.empty(); }
  // Polygon i, its planes copied out.
  PlanePolygon operator[](std::size_t i) const;
  GridPlane support(std::size_t i) const { return plane(refs_[runs_[i].first]); }
  std::uint32_t source(std::size_t i) const { return runs_[i].source; }

  void reserve(std::size_t polygons, std::size_t refs);
  // Appends a polygon by reference; the planes referred to are set by adopt() (before any read).
  void push_back(PlaneRef support, std::span<const PlaneRef> bounds, std::uint32_t source);
  // The arrays the references point into.
  void adopt(PageVector<GridPlane> own, std::vector<GridPlane> pooled);
  // Polygon i becomes `poly`, its planes appended to `own` (for polygons made by hand).
  void replace(std::size_t i, const PlanePolygon& poly);

 private:
  struct Run {
    std::uint32_t first = 0, count = 0;  // refs_[first] is the support, then `count - 1` bounds
    std::uint32_t source = 0;
  };
  GridPlane plane(PlaneRef r) const;
  PlaneRef own_ref(const GridPlane& p);

  std::vector<Run> runs_;
  std::vector<PlaneRef> refs_;
  PageVector<GridPlane> own_;
  std::vector<GridPlane> pooled_;
};

}  // namespace bsp
