#pragma once
// Proving an occlusion-culled fragment set conservative with Embree: primary rays from the eye
// through a pixel grid over the view's near rectangle and through sample points of every fragment
// in the view (its centroid and vertices pulled toward it, as validation_rays). A ray's first hit
// inside the view volume must be a fragment in the set, or tied with one (EmbreeScene::tie_reason:
// where geometry leaves their order open, either may be the one seen). Also measures how tight the
// set is: how many fragments are the first hit of some ray.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tree/traverse_culled.h"
#include "tree/tree.h"

namespace bsp {

struct OcclusionCheckSettings {
  int grid = 64;             // rays per side of the pixel grid
  double vertex_pull = 0.1;  // as ValidationSettings::vertex_pull
};

struct OcclusionCheck {
  std::uint64_t rays = 0;               // cast
  std::uint64_t rays_hitting = 0;       // with a hit inside the view volume
  // Rays whose Embree hits did not show an emitted first hit, recomputed exactly against every
  // fragment: Embree's float candidates can lose a fragment met at a grazing angle.
  std::uint64_t rays_rechecked = 0;
  std::uint64_t missed_rays = 0;        // whose first hit (and all tied with it) is not in the set
  std::uint64_t missed_fragments = 0;   // distinct fragments first hit by a missed ray
  std::uint64_t seen_fragments = 0;     // distinct fragments first hit by some ray
  std::vector<std::string> first_problems;  // up to 10
  bool ok() const { return missed_rays == 0; }
};

OcclusionCheck check_occlusion(const Tree& tree, const Frustum& view, std::span<const std::uint32_t> emitted,
                               const OcclusionCheckSettings& settings = {});

}  // namespace bsp
