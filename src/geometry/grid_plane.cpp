#include "geometry/grid_plane.h"

#include <cstdlib>

namespace bsp {

namespace {

struct Wide3 {
  Int128 x, y, z;
};

Wide3 difference(const GridPoint& q, const GridPoint& p) {
  return {Int128{q.x} - p.x, Int128{q.y} - p.y, Int128{q.z} - p.z};
}

Wide3 cross(const Wide3& e, const Wide3& f) {
  return {e.y * f.z - e.z * f.y, e.z * f.x - e.x * f.z, e.x * f.y - e.y * f.x};
}

GridPlane plane_with_normal(const Wide3& n, const GridPoint& p) {
  return {n.x, n.y, n.z, -(n.x * p.x + n.y * p.y + n.z * p.z)};
}

Int128 magnitude(Int128 v) { return v < 0 ? -v : v; }

}  // namespace

std::optional<GridPlane> plane_through(const GridPoint& p, const GridPoint& q, const GridPoint& r) {
  const Wide3 n = cross(difference(q, p), difference(r, p));
  if (n.x == 0 && n.y == 0 && n.z == 0) return std::nullopt;
  return plane_with_normal(n, p);
}

std::optional<GridPlane> edge_plane(const GridPoint& p, const GridPoint& q, const GridPlane& support,
                                    const GridPoint& inside) {
  if (p == q) return std::nullopt;
  // The axis of support's largest normal component is not parallel to the support plane.
  const Int128 ax = magnitude(support.a), ay = magnitude(support.b), az = magnitude(support.c);
  const Wide3 axis = ax >= ay && ax >= az ? Wide3{1, 0, 0} : ay >= az ? Wide3{0, 1, 0} : Wide3{0, 0, 1};
  const GridPlane plane = plane_with_normal(cross(difference(q, p), axis), p);
  const int side = plane.side(inside);
  if (side == 0) return std::nullopt;
  return side > 0 ? plane : -plane;
}

}  // namespace bsp
