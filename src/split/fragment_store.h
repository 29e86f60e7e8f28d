#pragma once
// Scratch storage for fragments during a build: polygons with their pooled supporting planes and
// bounding spheres in parallel arrays. The sphere lets most classifications decide with one
// plane evaluation instead of one per vertex.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "geometry/polygon.h"

namespace bsp {

struct BoundingSphere {
  Vec3 center;
  double radius = 0;
};

// Centred at the vertex average, reaching the farthest vertex.
BoundingSphere bounding_sphere(const Polygon& poly);

struct SideCounts {
  std::uint32_t front = 0, back = 0, coplanar = 0, spanning = 0;
};

class FragmentStore {
 public:
  std::uint32_t add(Polygon&& poly, std::uint32_t plane);
  // Adds a fragment whose bounding sphere is known (moved from another store).
  std::uint32_t add(Polygon&& poly, std::uint32_t plane, const BoundingSphere& sphere);
  std::size_t size() const { return polys_.size(); }
  void reserve(std::size_t n);

  const Polygon& poly(std::uint32_t id) const { return polys_[id]; }
  std::uint32_t plane(std::uint32_t id) const { return plane_[id]; }
  const BoundingSphere& sphere(std::uint32_t id) const { return sphere_[id]; }

  // classify() with a bounding-sphere early-out; identical results. Inline: it is the build's
  // innermost operation, and the early-out decides most calls with one plane evaluation.
  Side classify(std::uint32_t id, const Plane& p, double eps) const {
    const BoundingSphere& s = sphere_[id];
    const double d = p.distance(s.center);
    if (d - s.radius > eps) return Side::Front;
    if (d + s.radius < -eps) return Side::Back;
    return bsp::classify(polys_[id], p, eps);
  }
  SideCounts count_sides(std::span<const std::uint32_t> ids, const Plane& p, double eps) const;

  // Moves a fragment out when it is stored at a node or replaced by its split parts.
  Polygon take(std::uint32_t id) { return std::move(polys_[id]); }

 private:
  std::vector<Polygon> polys_;
  std::vector<std::uint32_t> plane_;
  std::vector<BoundingSphere> sphere_;
};

// IS-CONVEX-SET [DividingPolygon]: every fragment lies in front of or on every other fragment's plane.
// O(k^2) plane tests in the worst case, with an early exit on the first failure.
bool is_convex_set(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                   const PlanePool& planes, double eps);

}  // namespace bsp
