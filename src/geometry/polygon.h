#pragma once
// Convex planar polygons with per-vertex texture coordinates, and their classification against and
// splitting by a plane.
//
// Notation: d_i is the signed distance of vertex i to the plane; eps is Tolerance::plane_eps.
// A vertex is ON the plane when |d_i| <= eps, FRONT when d_i > eps, BACK when d_i < -eps.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "geometry/vec3.h"

namespace bsp {

struct Vertex {
  Vec3 p;
  double u = 0, v = 0;  // texture coordinates, interpolated linearly along split edges
};

struct Polygon {
  std::vector<Vertex> verts;  // counter-clockwise seen from the front of its plane
  std::uint32_t source = 0;   // index of the input polygon this one is (a fragment of)
};

enum class Side : std::uint8_t { Front, Back, Coplanar, Spanning };

// Newell's normal: length is twice the area; robust for nearly collinear vertices.
Vec3 newell_normal(const Polygon& poly);
Vec3 newell_normal(std::span<const Vec3> points);
double area(const Polygon& poly);
Vec3 centroid(const Polygon& poly);  // vertex average (exact for the convex fragments' samples)
// Supporting plane through the centroid; nullopt for a degenerate polygon (zero area).
std::optional<Plane> supporting_plane(const Polygon& poly);
double longest_edge(const Polygon& poly);
// The signed volume closed polygons enclose (divergence theorem, each polygon fanned from its first
// vertex): positive when they face outwards.
double enclosed_volume(std::span<const Polygon> polys);

Side classify(const Polygon& poly, const Plane& plane, double eps);
Side classify(std::span<const Vec3> points, const Plane& plane, double eps);
// True when no vertex is behind the plane by more than eps (front or on it).
bool in_front_or_on(const Polygon& poly, const Plane& plane, double eps);
bool in_front_or_on(std::span<const Vec3> points, const Plane& plane, double eps);

// Removes every vertex within eps of the vertex kept before it (and trailing ones within eps of the
// first): two vertices closer than the tolerance are one point, and an edge that short has no
// reliable direction (a cut point interpolated within rounding of its edge's end lands there).
// A convex polygon stays convex and inside the original. Returns the area removed.
double merge_close_vertices(Polygon& poly, double eps);

// A fragment narrower than eps (area / longest edge < eps) or with fewer than 3 vertices is a
// sliver; splitting drops it and reports it here.
struct SplitResult {
  std::optional<Polygon> front, back;
  int dropped = 0;            // slivers dropped by this split (0, 1 or 2)
  double dropped_area = 0.0;  // their total area, plus the area merge_close_vertices shaved off the parts
};

// Splits a polygon classified Spanning; both parts keep `source`. Each part is convex, and the
// parts partition the polygon: vertices go by the exact sign of their distance.
SplitResult split(const Polygon& poly, const Plane& plane, double eps);

// split() into two polygons the caller owns, so a caller splitting many reuses their memory: both
// are overwritten, and `front` / `back` say which parts were kept (not slivers).
struct SplitKept {
  bool front = false, back = false;
  int dropped = 0;            // as SplitResult
  double dropped_area = 0.0;  // as SplitResult
};
SplitKept split_into(const Polygon& poly, const Plane& plane, double eps, Polygon& front, Polygon& back);
// split_into's front part alone (the back part is never computed): true when it is kept; `front`
// is overwritten either way.
bool front_part_into(const Polygon& poly, const Plane& plane, double eps, Polygon& front);
bool is_sliver(const Polygon& poly, double eps);

}  // namespace bsp
