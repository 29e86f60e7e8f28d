#pragma once
// Ray shooting: the first fragment a ray hits, found by walking the tree front to back along the
// ray (the classic BSP ray traversal; Naylor's E_line, expected_cost.h, models its cost). The walk
// keeps a stack of (node, tmin, tmax) segments of the ray clipped to the scene box: at a node whose
// plane the segment crosses at t_c it visits the near side on [tmin, t_c], then the fragments stored
// on the plane at t_c, then the far side on [t_c, tmax]; a segment wholly on one side visits that
// side only. Coarse leaves test all their fragments. The walk stops at the first segment starting
// at or beyond the nearest hit found so far: segments are popped in order of increasing tmin, and
// every fragment lies in the cell of the node storing it, so nothing later can be nearer (up to
// ties within the plane tolerance). No recursion.
//
// Ray and Hit are those of the Embree checker (validate/embree_scene.h), whose first_hit must give
// the same answer on every ray (ties aside): an independent check of the tree.
#include <cstdint>
#include <optional>

#include "tree/tree.h"
#include "validate/embree_scene.h"

namespace bsp {

// Where the ray meets the convex polygon, as the ray parameter t > 0 on the polygon's supporting
// plane `support`; nullopt when it misses or runs parallel to the plane. Inclusion uses the signs
// of the ray's Plücker products with the polygon's edges (all >= 0 or all <= 0), which are exactly
// opposite for an edge shared by two polygons, so a ray cannot slip between neighbours.
std::optional<double> ray_polygon_hit(const Ray& ray, const Polygon& poly, const Plane& support);

struct RayShot {
  std::optional<Hit> hit;            // the nearest fragment hit at t > 0
  std::uint32_t nodes_visited = 0;   // nodes whose segment the walk processed
  std::uint32_t fragment_tests = 0;  // ray_polygon_hit calls
};

RayShot shoot_ray(const Tree& tree, const Ray& ray);

}  // namespace bsp
