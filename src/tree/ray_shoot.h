#pragma once
// Ray shooting: the first fragment a ray hits, found by walking the tree front to back along the
// ray (the classic BSP ray traversal; Naylor's E_line, expected_cost.h, models its cost). The walk
// keeps a stack of (node, tmin, tmax) segments of the ray clipped to the scene box. A fragment lies
// in the cell of the node storing it only up to plane_eps (the build files a fragment within
// plane_eps of a plane on one side of it), so at a node the walk visits the near side on the part
// of the segment within plane_eps of the near half-space, then the fragments stored at the node
// when the segment comes within plane_eps of its plane, then the far side on the part within
// plane_eps of the far half-space; a segment farther than plane_eps from the plane visits one side
// only. Coarse leaves test all their fragments. Segments starting at or beyond the nearest hit
// found so far are skipped: nothing they hold can be nearer. No recursion.
//
// The Embree checker (validate/embree_scene.h) takes the same rays, and its first hit must give
// the same answer on every ray (ties aside): an independent check of the tree.
#include <cstdint>
#include <optional>
#include <span>

#include "geometry/ray.h"
#include "tree/tree.h"

namespace bsp {

// Where the ray meets the convex polygon, as the ray parameter t > 0 on the polygon's supporting
// plane `support`; nullopt when it misses or runs parallel to the plane. Inclusion uses the signs
// of the ray's Plücker products with the polygon's edges (all >= 0 or all <= 0), which are exactly
// opposite for an edge shared by two polygons, so a ray cannot slip between neighbours. Each
// product is taken as e · (dir × (u - origin)) from the edge's lexicographically smaller end u:
// the cross product then only cancels down to the ray's distance from u, so a far eye looking at
// a tiny fragment keeps the sign (the plain dir · ((a - o) × (b - o)) loses it to rounding of
// |a - o|^2, at 5e4 units for a fragment 1e-4 wide).
std::optional<double> ray_polygon_hit(const Ray& ray, std::span<const Vec3> polygon, const Plane& support);

struct RayShot {
  std::optional<RayHit> hit;         // the nearest fragment hit at t > 0
  std::uint32_t nodes_visited = 0;   // nodes whose segment the walk processed
  std::uint32_t fragment_tests = 0;  // ray_polygon_hit calls
};

RayShot shoot_ray(const Tree& tree, const Ray& ray);

}  // namespace bsp
