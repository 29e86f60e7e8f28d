#pragma once
// Convex polygons as bare point loops (no texture coordinates, no source): the sub-hyperplanes of
// solid trees and the faces cut from their cells.
//
// Notation: d_i is the signed distance of loop vertex i to the plane, eps the on-plane tolerance.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "geometry/polygon.h"
#include "geometry/vec3.h"

namespace bsp {

// Convex loops in one array; loop i is points[start[i], start[i + 1]).
struct LoopPool {
  std::vector<Vec3> points;
  std::vector<std::uint32_t> start = std::vector<std::uint32_t>(1, 0);

  std::uint32_t add(std::span<const Vec3> loop);
  std::span<const Vec3> operator[](std::uint32_t i) const {
    return {points.data() + start[i], start[i + 1] - start[i]};
  }
  std::size_t size() const { return start.size() - 1; }
};

// Splits a convex loop by a plane (Sutherland–Hodgman on both sides at once). A vertex with
// |d_i| <= eps goes to both parts; an edge whose ends lie beyond eps on opposite sides is cut where
// the distance changes sign. A part with fewer than 3 vertices comes back empty. `front` and
// `back` are overwritten, so a caller splitting many loops reuses their memory.
void split_loop(std::span<const Vec3> loop, const Plane& plane, double eps, std::vector<Vec3>& front,
                std::vector<Vec3>& back);

// Where edge ab crosses a plane, given the ends' distances da and db of opposite signs, computed
// from the lexicographically smaller end: the two faces that share an edge cut it at the same
// point, bit for bit.
Vec3 edge_cut(const Vec3& a, const Vec3& b, double da, double db);

// The part of the plane inside the box, counter-clockwise about the plane's normal (its Newell
// normal points along n). Empty when the plane misses the box.
std::vector<Vec3> plane_in_box(const Plane& plane, const Box& box);

// Where a loop lying in plane `own` is against `plane`: Coplanar only when the two planes are
// parallel (kParallelCosineSlack) and every vertex is within eps; otherwise Front, Back or
// Spanning with eps, and, for a loop within eps of a plane it is not parallel to, by the exact
// sign of each vertex (Front when every vertex is exactly on it).
Side classify_loop(std::span<const Vec3> loop, const Plane& own, const Plane& plane, double eps);

// The side of the plane a loop lies on, decided by its farthest vertex: Front when the largest
// distance beyond the plane is at least the largest behind it. Used where a tolerance decision
// said Spanning or Coplanar but the geometry admits only one side.
bool mostly_in_front(std::span<const Vec3> loop, const Plane& plane);

}  // namespace bsp
