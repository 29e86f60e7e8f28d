#pragma once
// Rays and ray hits, shared by the tree's ray shooting (tree/ray_shoot.h) and the independent
// Embree checker (validate/embree_scene.h), which must agree on every ray.
#include <cstdint>

#include "geometry/vec3.h"

namespace bsp {

// A ray from origin along dir (any nonzero length); points are origin + t * dir.
struct Ray {
  Vec3 origin, dir;
};

// Where a ray meets a fragment.
struct RayHit {
  double t = 0.0;              // ray parameter of the hit, t >= 0
  std::uint32_t fragment = 0;  // index of the fragment hit
};

}  // namespace bsp
