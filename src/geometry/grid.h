#pragma once
// The integer grid of the exact kernel: every input vertex is snapped to a point of a scene's grid,
// so every plane through three vertices has integer coefficients of bounded size
// (geometry/grid_plane.h) and every predicate on them can be decided exactly
// (geometry/exact_predicates.h) [Sugihara1989] [BernsteinFussell2009].
//
// The grid of a scene: origin at the centre of the scene's box, spacing `step` the largest power of
// two with step * sqrt(3) / 2 <= kSnapRelative * diagonal. Rounding each coordinate to the nearest
// multiple moves a point by at most step / 2 per axis, step * sqrt(3) / 2 in all, so at most
// kSnapRelative of the diagonal (the subtraction of the origin adds at most one rounding of 2^-53
// relative to the half-diagonal, four orders of magnitude below the grid). A point of the box is at
// most half the diagonal from the origin on each axis and step > kSnapRelative * diagonal / sqrt(3),
// so its grid coordinates are below sqrt(3) / (2 * kSnapRelative) + 1/2 < 8.7e11 < 2^kGridBits.
// Powers of two make origin + q * step exact up to the final addition.
#include <cstdint>
#include <optional>

#include "geometry/vec3.h"

namespace bsp {

// How far snapping may move a vertex, relative to the scene's diagonal: the near-degenerate
// scene's features of 1e-9 of the diagonal are a thousand grid steps wide.
inline constexpr double kSnapRelative = 1e-12;
// |grid coordinate| < 2^kGridBits for every point of the scene's box.
inline constexpr int kGridBits = 40;

struct GridPoint {
  std::int64_t x = 0, y = 0, z = 0;
  friend bool operator==(const GridPoint&, const GridPoint&) = default;
};

// What snapping moved (best: nothing; worst: every vertex by kSnapRelative of the diagonal).
struct SnapStats {
  std::uint64_t vertices = 0;
  std::uint64_t moved = 0;         // vertices not already on the grid
  double max_displacement = 0.0;   // in scene units
  double sum_displacement = 0.0;   // over all vertices; mean = sum / vertices
  void add(double displacement);
  double mean_displacement() const { return vertices ? sum_displacement / static_cast<double>(vertices) : 0.0; }
};

class Grid {
 public:
  // The grid of a box with finite coordinates; an empty or degenerate box gets the grid of a
  // box of diagonal 1 around its centre (every point snaps to itself or near it).
  static Grid for_box(const Box& box);

  double step() const { return step_; }
  const Vec3& origin() const { return origin_; }
  // The nearest grid point; nullopt for a point outside the grid's range (|coordinate| >=
  // 2^kGridBits), which no point of the box is.
  std::optional<GridPoint> snap(const Vec3& p) const;
  // The scene point of a grid point (rounded once, by the final addition of the origin).
  Vec3 point(const GridPoint& q) const;

 private:
  Grid(const Vec3& origin, double step) : origin_(origin), step_(step) {}
  Vec3 origin_;
  double step_;
};

}  // namespace bsp
