#include "geometry/grid.h"

#include <algorithm>
#include <cmath>

namespace bsp {

void SnapStats::add(double displacement) {
  ++vertices;
  if (displacement > 0) ++moved;
  max_displacement = std::max(max_displacement, displacement);
  sum_displacement += displacement;
}

Grid Grid::for_box(const Box& box) {
  double diagonal = box.diagonal();
  const Vec3 origin = box.empty() || !is_finite(box.center()) ? Vec3{} : box.center();
  // Below 1e-280 the step would leave the normal doubles, where q * step is no longer exact.
  if (!(diagonal > 1e-280) || !std::isfinite(diagonal)) diagonal = 1.0;
  const double bound = 2.0 * kSnapRelative * diagonal / std::sqrt(3.0);
  double step = std::exp2(std::floor(std::log2(bound)));
  while (step > bound) step *= 0.5;  // log2 and floor may round across a power of two
  while (step * 2.0 <= bound) step *= 2.0;
  return Grid(origin, step);
}

std::optional<GridPoint> Grid::snap(const Vec3& p) const {
  // Dividing by a power of two is exact; only the subtraction rounds.
  const Vec3 d = (p - origin_) / step_;
  constexpr double kLimit = static_cast<double>(std::int64_t{1} << kGridBits) - 0.5;
  if (!(std::abs(d.x) < kLimit && std::abs(d.y) < kLimit && std::abs(d.z) < kLimit)) return std::nullopt;
  return GridPoint{std::llround(d.x), std::llround(d.y), std::llround(d.z)};
}

Vec3 Grid::point(const GridPoint& q) const {
  return origin_ + Vec3{static_cast<double>(q.x), static_cast<double>(q.y), static_cast<double>(q.z)} * step_;
}

}  // namespace bsp
