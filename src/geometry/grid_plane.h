#pragma once
// Planes of the exact kernel: a x + b y + c z + d = 0 in grid coordinates (geometry/grid.h), with
// integer coefficients, through three grid points. Positive values are the plane's front.
//
// Bounds, for grid points p, q, r (|coordinate| < 2^40 = 2^kGridBits):
//  - the edges q - p and r - p have |components| < 2^41;
//  - the normal (q - p) x (r - p) has |a|, |b|, |c| < 2 * 2^41 * 2^41 = 2^83 (kNormalBits);
//  - d = -normal . p has |d| < 3 * 2^83 * 2^40 < 2^125 (kOffsetBits);
//  - a plane's value at a grid point, normal . x + d, is below 3 * 2^123 + 3 * 2^123 < 2^126.
// So coefficients and values fit a signed 128-bit integer with room to spare, and the predicates'
// determinants have bounded width (geometry/exact_predicates.h). Every plane the exact kernel
// uses is of this kind; an edge plane (below) is one with smaller coefficients still.
#include <optional>

#include "geometry/grid.h"
#include "geometry/wide_int.h"

namespace bsp {

inline constexpr int kNormalBits = 2 * (kGridBits + 1) + 1;  // |a|, |b|, |c| < 2^83
inline constexpr int kOffsetBits = kNormalBits + kGridBits + 2;  // |d| < 2^125
static_assert(kOffsetBits + 1 < 127, "a plane's value at a grid point must fit Int128");

struct GridPlane {
  Int128 a = 0, b = 0, c = 0, d = 0;

  GridPlane operator-() const { return {-a, -b, -c, -d}; }
  friend bool operator==(const GridPlane&, const GridPlane&) = default;
  // a x + b y + c z + d, exactly.
  Int128 value(const GridPoint& p) const { return a * p.x + b * p.y + c * p.z + d; }
  // +1 in front, -1 behind, 0 on the plane.
  int side(const GridPoint& p) const {
    const Int128 v = value(p);
    return (v > 0) - (v < 0);
  }
};

// The plane through p, q and r, whose front is where (q - p) x (r - p) points (r seen
// counter-clockwise from p and q); nullopt when the three are collinear.
std::optional<GridPlane> plane_through(const GridPoint& p, const GridPoint& q, const GridPoint& r);

// A bounding plane for the edge from p to q of a face on `support`: the plane through p, q and
// p + the unit vector of the axis along which support's normal is largest, which therefore meets
// the support plane exactly in the line pq. Its normal has components below 2^41 and its offset
// below 2^83. Front: the side of `inside` (a grid point of the face off the line pq). nullopt when
// p == q or `inside` is on the line.
std::optional<GridPlane> edge_plane(const GridPoint& p, const GridPoint& q, const GridPlane& support,
                                    const GridPoint& inside);

}  // namespace bsp
