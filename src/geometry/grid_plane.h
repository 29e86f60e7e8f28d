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
#include "geometry/plane.h"
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

// The plane divided by the greatest common divisor of its coefficients, orientation kept: two
// grid planes through the same points with the same front are then equal coefficient for
// coefficient, so a pool can share them by comparing integers. The zero plane stays zero.
GridPlane canonical(const GridPlane& p);

// Rounding a free plane (one a splitter chose through no three grid points: halving's, a dynamic
// scene's object planes) to a grid plane, the kernel's one rounding of a plane. The rule: in grid
// coordinates the plane is n . g + (n . origin + d) / step = 0; scale it by the power of two
// 2^e that brings its largest normal component into [2^(kFreeNormalBits - 1), 2^kFreeNormalBits),
// round each normal component and the offset to the nearest integer (the scaling is exact; the
// offset n . origin + d is computed in doubles first, a few roundings of u |origin| each), and
// take canonical(). The rule is deterministic; how far it moves the plane: the normal turns by at
// most about 2^(1 - kFreeNormalBits) radians (about 1.4 grid steps across the grid's reach), and
// the offset moves by half a step plus the doubles' rounding, a few u |origin| / step steps (for a
// scene whose box is far from the world's origin, tens of steps). Coefficients stay below an edge
// plane's (normal < 2^41, offset < 2^83), inside the predicates' bounds. nullopt when the plane
// lies beyond every grid point (its offset would reach kFreeOffsetLimit: every grid point's value
// n . g is below 3 * 2^kFreeNormalBits * 2^kGridBits < 2^82, so it cuts nothing) or has a zero or
// non-finite normal.
inline constexpr int kFreeNormalBits = 40;
inline constexpr double kFreeOffsetLimit = 0x1p82;
static_assert(kFreeNormalBits + kGridBits + 2 <= 82, "a rounded plane beyond kFreeOffsetLimit must miss every grid point");
std::optional<GridPlane> round_plane(const Plane& p, const Grid& grid);

}  // namespace bsp
