#include "split/fragment_store.h"

namespace bsp {

BoundingSphere bounding_sphere(const Polygon& poly) {
  BoundingSphere s{centroid(poly), 0.0};
  for (const auto& v : poly.verts) s.radius = std::max(s.radius, length(v.p - s.center));
  return s;
}

std::uint32_t FragmentStore::add(Polygon&& poly, std::uint32_t plane) {
  return add(std::move(poly), plane, bounding_sphere(poly));
}

std::uint32_t FragmentStore::add(Polygon&& poly, std::uint32_t plane, const BoundingSphere& s) {
  polys_.push_back(std::move(poly));
  plane_.push_back(plane);
  sphere_.push_back(s);
  return static_cast<std::uint32_t>(polys_.size() - 1);
}

void FragmentStore::reserve(std::size_t n) {
  polys_.reserve(n);
  plane_.reserve(n);
  sphere_.reserve(n);
}

SideCounts FragmentStore::count_sides(std::span<const std::uint32_t> ids, const Plane& p, double eps) const {
  SideCounts c;
  for (auto id : ids) {
    switch (classify(id, p, eps)) {
      case Side::Front: ++c.front; break;
      case Side::Back: ++c.back; break;
      case Side::Coplanar: ++c.coplanar; break;
      case Side::Spanning: ++c.spanning; break;
    }
  }
  return c;
}

bool is_convex_set(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                   const PlanePool& planes, double eps) {
  for (auto a : ids) {
    const Plane& pa = planes[frags.plane(a)];
    for (auto b : ids) {
      if (a == b) continue;
      const BoundingSphere& s = frags.sphere(b);
      if (pa.distance(s.center) - s.radius >= -eps) continue;
      if (!in_front_or_on(frags.poly(b), pa, eps)) return false;
    }
  }
  return true;
}

}  // namespace bsp
