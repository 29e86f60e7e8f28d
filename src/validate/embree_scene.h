#pragma once
// An independent ray caster for checking BSP results: the fragments, fan-triangulated, in one
// Embree scene. Embree never appears in this header (pimpl), so including it costs nothing.
//
// Technique (Embree's all-hits filter [Wald2014]): rays are cast in packets of 16 (rtcIntersect16)
// with an intersection filter that records every hit (ray id, primitive) and rejects it, so
// traversal continues to the end of every ray. The scene is built with RTC_SCENE_FLAG_ROBUST
// (without it ~10% of rays aimed at shared edges leak through).
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
//     t >= 0 at a point inside the fragment or within kInsideEps × plane_eps of its boundary;
//     t is that meeting point's ray parameter. Rays lying in a fragment's plane do not hit it.
// Ties (Hit, tie_reason): two hits on a ray are a tie only when geometry leaves their order open.
// A BSP decides sides with plane_eps, so within plane_eps of each other two fragments may lie either
// way; elsewhere their order along a ray is a fact. The reasons, in the order they are tested:
//  - edge: the ray meets both within the hit radius of a point c where they touch: c lies on an
//    edge of one fragment, within plane_eps of the other's plane and inside it (a shared edge, or an
//    edge resting on the other's face, as a wall stands on a floor);
//  - coplanar: where the ray meets them, the planes coincide within plane_eps: one hit lies within
//    plane_eps of the other fragment's plane (the distance along the ray times the sine of the
//    ray's angle to that plane, the sine floored at 1 / kMaxGrazingScale). A BSP files a fragment
//    whose vertices lie within plane_eps of a plane on either side of it, so there the order is
//    open: overlapping coplanar polygons, two parts of one split polygon, near-coplanar layers
//    (two fragments within plane_eps of one node's plane, so up to 2 plane_eps apart);
//  - boundary: otherwise, when one hit lies outside its fragment by less than the boundary slack
//    (kInsideEps × plane_eps): whether the ray meets that fragment at all is below what the
//    fragments' own planarity lets the double-precision test decide. That leaves open which
//    fragment this ray meets first (ray shooting), but not always the pair's order: when a ray
//    turned about its origin just far enough to meet the outside hit's fragment still meets the
//    other fragment inside (overlap_nearby), the two overlap on screen and the order is a fact.
// The hit radius of a hit is how far its computed point can be from where the ray truly meets the
// fragment: the boundary slack of the double-precision test plus plane_eps (the fragment's own
// planarity) divided by the sine of the angle between the ray and the fragment's plane, that
// division capped at kMaxGrazingScale. Any other pair is judged, however close its hits.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometry/polygon.h"
#include "geometry/ray.h"
#include "geometry/vec3.h"

namespace bsp {

// Boundary slack of the double-precision hit test, in plane_eps: a ray through an edge shared by two
// fragments (whose planes fit their vertices to within plane_eps) hits at least one of them.
inline constexpr double kInsideEps = 1.0;
// Cap on 1 / sin(angle between a ray and a fragment's plane) in the hit radius: a ray grazing a
// plane at a sine below 1e-3 (0.06 degrees) gets the radius of one at 1e-3, so the radius stays
// below ~1e-6 scene diagonals instead of growing without bound.
inline constexpr double kMaxGrazingScale = 1e3;
// How far Embree's copy of each fragment is grown. Float rounding moves a ray by ~1e-7 diagonals
// across its length; where the ray meets a plane at a sine s, that moves the meeting point by
// ~1e-7 / s in the plane. 1e-4 covers every ray down to s = 1e-3 (kMaxGrazingScale), so Embree
// cannot lose a candidate the double test would accept there.
inline constexpr double kGrowRelative = 1e-4;

// A hit as the checker decides it, with what it needs to judge ties.
struct Hit : RayHit {
  double depth = 0.0;    // distance from the ray's origin, world units: t * |dir|
  double radius = 0.0;   // the hit radius (header), world units
  double inside = 0.0;   // distance of the hit point from the fragment's boundary, < 0 outside
  double grazing = 1.0;  // 1 / sine of the angle between ray and fragment plane, capped at kMaxGrazingScale
};

enum class TieReason : std::uint8_t { None, Coplanar, Edge, Boundary };

// The hits of a batch of rays. A caller keeps one per thread and passes it to every call, so casting
// allocates nothing once the buffers have grown.
struct HitBatch {
  std::vector<Hit> hits;             // ray r's hits are hits[first[r], first[r + 1])
  std::vector<std::uint32_t> first;  // one entry per ray, plus one
  std::vector<std::uint64_t> keys;   // scratch: (ray << 32 | triangle) as Embree proposes them
  std::vector<std::uint32_t> frags;  // scratch: the keys' fragments, grouped by ray

  std::span<const Hit> of(std::size_t r) const { return {hits.data() + first[r], first[r + 1] - first[r]}; }
};

class EmbreeScene {
 public:
  // Fragments must be convex planar polygons (zero-area ones are never hit). plane_eps is the
  // tolerance the fragments were made with (Tree::tol); by default that of their bounding box
  // (Tolerance::for_extent). Throws std::runtime_error when Embree fails or lacks what the
  // technique needs (filter functions supported, backface culling off).
  explicit EmbreeScene(std::span<const Polygon> fragments, std::optional<double> plane_eps = std::nullopt);
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&&) noexcept;
  EmbreeScene& operator=(EmbreeScene&&) noexcept;

  // Every fragment the ray meets at t >= 0, once each, sorted by (t, fragment). Thread-safe.
  std::vector<Hit> all_hits(const Ray& ray) const;
  // all_hits of every ray, into `out` (out.of(r) for rays[r]). Casting many rays at once lets Embree
  // trace them as packets. Thread-safe with one HitBatch per thread.
  void all_hits(std::span<const Ray> rays, HitBatch& out) const;
  // Exactly all_hits(ray).front(): the nearest hit (smallest fragment id on an exact tie). A
  // fragment tied with it (tie_reason) is equally entitled to be first. Thread-safe.
  std::optional<Hit> first_hit(const Ray& ray) const;
  // The nearest of hit(ray, f) over every fragment f, without Embree: O(fragments), for the rays
  // where Embree's float candidates cannot be trusted (a ray meeting a plane at a sine below
  // 1 / kMaxGrazingScale may lose its candidate). Same tie-breaking as first_hit.
  std::optional<Hit> first_hit_exhaustive(const Ray& ray) const;
  // The double-precision decision for one fragment, without Embree: where the ray meets it, if it
  // does. all_hits returns exactly these hits for the fragments Embree proposes.
  std::optional<Hit> hit(const Ray& ray, std::uint32_t fragment) const;
  // Why two hits of one ray cannot be ordered (header), or None when they can.
  TieReason tie_reason(const Ray& ray, const Hit& a, const Hit& b) const;
  // For a boundary tie: whether the ray, turned about its origin until it meets the outside hit's
  // fragment, certainly still meets the other one. Turning it by the outside distance d at the
  // outside hit's depth t_o moves the other hit by at most d * (t_other / t_o) / sin(other's
  // grazing angle, capped as in the hit radius); the other hit must lie farther than that plus
  // the boundary slack inside its fragment. Then both fragments cover one point of the screen,
  // and their order along the turned ray is the order along this one.
  bool overlap_nearby(const Hit& a, const Hit& b) const;

  double plane_eps() const;
  std::size_t fragment_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bsp
