#include "geometry/plane_polygon_set.h"

#include <limits>
#include <stdexcept>
#include <utility>

namespace bsp {

GridPlane PlanePolygonSet::plane(PlaneRef r) const {
  if (!(r & kPooled)) return own_[r];
  const std::uint32_t i = r & ~kPooled;
  return (i & 1u) ? -pooled_[i >> 1] : pooled_[i >> 1];
}

PlanePolygon PlanePolygonSet::operator[](std::size_t i) const {
  const Run& run = runs_[i];
  PlanePolygon out{plane(refs_[run.first]), {}, run.source};
  out.bounds.reserve(run.count - 1);
  for (std::uint32_t k = 1; k < run.count; ++k) out.bounds.push_back(plane(refs_[run.first + k]));
  return out;
}

void PlanePolygonSet::reserve(std::size_t polygons, std::size_t refs) {
  runs_.reserve(polygons);
  refs_.reserve(refs);
}

void PlanePolygonSet::push_back(PlaneRef support, std::span<const PlaneRef> bounds, std::uint32_t source) {
  if (refs_.size() + bounds.size() + 1 > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("a plane polygon set holds more than 2^32 plane references");
  runs_.push_back({static_cast<std::uint32_t>(refs_.size()), static_cast<std::uint32_t>(bounds.size() + 1), source});
  refs_.push_back(support);
  refs_.insert(refs_.end(), bounds.begin(), bounds.end());
}

void PlanePolygonSet::adopt(PageVector<GridPlane> own, std::vector<GridPlane> pooled) {
  own_ = std::move(own);
  pooled_ = std::move(pooled);
}

PlanePolygonSet::PlaneRef PlanePolygonSet::own_ref(const GridPlane& p) {
  if (own_.size() >= kPooled) throw std::length_error("a plane polygon set holds more than 2^31 planes");
  own_.push_back(p);
  return static_cast<PlaneRef>(own_.size() - 1);
}

void PlanePolygonSet::replace(std::size_t i, const PlanePolygon& poly) {
  std::vector<PlaneRef> bounds;
  for (const GridPlane& b : poly.bounds) bounds.push_back(own_ref(b));
  const PlaneRef support = own_ref(poly.support);
  const Run run{static_cast<std::uint32_t>(refs_.size()), static_cast<std::uint32_t>(bounds.size() + 1), poly.source};
  refs_.push_back(support);
  refs_.insert(refs_.end(), bounds.begin(), bounds.end());
  runs_[i] = run;
}

}  // namespace bsp
