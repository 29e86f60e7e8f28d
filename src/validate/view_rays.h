#pragma once
// Deterministic eye points and ray sets for checking visibility orders against Embree.
//
// Eyes: even-numbered eyes lie outside the scene box on spheres around it at 1.5, 2.5 and 4
// diagonals from its centre; odd-numbered ones lie inside it. Positions come from a fixed Rng
// stream, so every run uses the same eyes, yet (with probability 1) none lies on a scene plane,
// where a back-to-front order is ambiguous.
//
// Rays from one eye: through sample points of every fragment (its centroid and each vertex pulled
// toward the centroid, so every fragment is probed near its corners too), plus a pixel grid: over
// the box's projection for an eye that sees the whole box in front of it, or a cube map around an
// eye that does not (one inside the box or too close to it).
#include <span>
#include <vector>

#include "geometry/polygon.h"
#include "geometry/vec3.h"
#include "validate/embree_scene.h"

namespace bsp {

struct ValidationSettings {
  int views = 8;              // eye points for validate_tree: ceil(views/2) outside, floor(views/2) inside
  int grid = 48;              // pixels per side of an outside eye's grid over the box's projection
  int cube_grid = 24;         // pixels per side of each of the six cube-map faces of an inside eye
  double vertex_pull = 0.1;   // vertex sample = vertex + vertex_pull * (centroid - vertex), in (0, 1]
};

std::vector<Vec3> validation_eyes(const Box& box, int views);

// Directions are unit length; rays start at the eye.
std::vector<Ray> validation_rays(std::span<const Polygon> fragments, const Box& box, const Vec3& eye,
                                 const ValidationSettings& settings);

}  // namespace bsp
