#pragma once
// An independent ray caster for checking BSP results: the fragments, fan-triangulated, in one
// Embree scene. Embree never appears in this header (pimpl), so including it costs nothing.
//
// Technique (FACTS.md, Embree section): one rtcIntersect1 per ray with an intersection filter that
// records every hit and rejects it, so traversal continues to the end of the ray. The scene is
// built with RTC_SCENE_FLAG_ROBUST (without it ~10% of rays aimed at shared edges leak through).
// Callbacks arrive in traversal order and may repeat a primitive, so candidates are deduplicated
// per fragment and the hits sorted by t.
//
// Precision. Embree works in floats, and float answers are not good enough to order fragments
// that touch: a ray passing a float-ulp beside fragment A's edge gets reported as hitting A, and
// where the ray grazes A's plane that "hit" lies far along the ray from where the ray meets A's
// plane; a fan triangle narrower than a float ulp has a float plane pointing anywhere. So Embree
// only proposes candidates, and each is decided in double:
//  1. Embree sees every fragment grown outward in its plane by kGrowRelative × diagonal (far above
//     float rounding), so it proposes every fragment the ray truly meets, and more. Coordinates are
//     shifted to the scene box's centre and rays start where they enter the box, so float rounding
//     is relative to the scene's size, not to its position or the eye's distance.
//  2. A candidate is a hit when the ray meets the fragment's supporting plane (Newell normal) at
//     t >= 0 at a point inside the fragment or within kInsideRelative × diagonal of its boundary;
//     t is that meeting point's ray parameter. Rays lying in a fragment's plane do not hit it.
// Two hits whose distances differ by at most tie_tolerance() are ties: a ray through a shared
// edge, or coplanar overlapping fragments, or fragments that touch within the BSP's plane_eps.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometry/polygon.h"
#include "geometry/vec3.h"

namespace bsp {

// Ties: hits closer along a ray than kTieRelative × (diagonal of the fragments' bounding box) plus
// both hits' own depth uncertainty (Hit::slack). A hit's depth is exact up to the boundary slack
// kInsideRelative and the fragments' planarity tolerance (plane_eps = 1e-9 diagonals), divided by
// the sine of the angle between the ray and the fragment's plane: negligible for most rays, but a
// ray grazing a plane at a sine of 6e-4 has a depth uncertain by ~2e-5 diagonals, which the fixed
// kTieRelative alone would take for a real separation. 1e-5 stays far below any depth separation a
// scene means to have.
inline constexpr double kTieRelative = 1e-5;
// Boundary slack of the double-precision hit test: ten times plane_eps, so that a ray through an
// edge shared by two fragments (whose planes fit their vertices to within plane_eps) hits at least
// one of them.
inline constexpr double kInsideRelative = 1e-8;
// How far Embree's copy of each fragment is grown: ~30 float ulps of a coordinate in the centred
// box, so Embree's float rounding cannot lose a candidate the double test would accept.
inline constexpr double kGrowRelative = 1e-6;

// A ray from origin along dir (any nonzero length); points are origin + t * dir.
struct Ray {
  Vec3 origin, dir;
};

struct Hit {
  double t;                // ray parameter of the hit, t >= 0
  std::uint32_t fragment;  // index into the fragments the scene was built from
  double slack = 0.0;      // uncertainty of t: boundary slack / |plane normal · dir| (see kTieRelative)
};

class EmbreeScene {
 public:
  // Fragments must be convex planar polygons (zero-area ones are never hit). Throws
  // std::runtime_error when Embree fails or lacks what the technique needs (filter functions
  // supported, backface culling off).
  explicit EmbreeScene(std::span<const Polygon> fragments, double tie_relative = kTieRelative);
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;

  // Every fragment the ray meets at t >= 0, once each, sorted by (t, fragment). Thread-safe.
  std::vector<Hit> all_hits(const Ray& ray) const;
  // Exactly all_hits(ray).front(): the nearest hit (smallest fragment id on an exact tie). A
  // fragment within tie_tolerance() of it is equally entitled to be first; all_hits tells which.
  // Thread-safe.
  std::optional<Hit> first_hit(const Ray& ray) const;

  // Distance (world units, i.e. |Δt| × |dir|) at or below which two hits are a tie.
  double tie_tolerance() const;
  std::size_t fragment_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bsp
