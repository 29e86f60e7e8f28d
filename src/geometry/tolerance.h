#pragma once
// The one geometric tolerance of the suite, and the rule that scales it with the scene.
//
// plane_eps: a point whose signed distance to a plane is within ±plane_eps lies ON the plane.
// It decides front/back/coplanar/spanning for every classification in build, traversal and
// validation, and it is the width below which a split fragment counts as a sliver and is dropped
// (dropped slivers are counted with their area in BuildStats, never silently lost).
//
// Scaling: plane_eps = kPlaneEpsRelative * (diagonal of the scene's bounding box). Coordinates
// carry about 1e-16 relative rounding error and every split adds a few ulps; 1e-9 leaves six
// orders of magnitude of headroom for that while staying far below any feature a scene means to
// have. Scenes whose features are smaller than 1e-9 of their extent (the near-degenerate scene
// builds such on purpose) meet the tolerance and are reported through the sliver counters.
#include <algorithm>

namespace bsp {

inline constexpr double kPlaneEpsRelative = 1e-9;

// Two planes are parallel (so a loop within plane_eps of both lies in both) when the angle between
// their normals is below about 4.5e-5 rad: |cos| >= 1 - kParallelCosineSlack. Planes of faces
// that share a plane differ by rounding (1e-16); a free plane or a neighbouring face is far off.
// Without this test a loop smaller than plane_eps / angle counts as lying in every plane that
// passes near it, and goes whole to one side.
inline constexpr double kParallelCosineSlack = 1e-9;

struct Tolerance {
  double plane_eps = kPlaneEpsRelative;

  // `relative` is kPlaneEpsRelative everywhere but in the kernel runs that sweep it to measure
  // what the tolerance does (experiments/kernel/kernel.h).
  static Tolerance for_extent(double scene_diagonal, double relative = kPlaneEpsRelative) {
    return {relative * std::max(scene_diagonal, 1e-300)};
  }
};

}  // namespace bsp
