#pragma once
// Turning a face from a file into the convex planar polygons a build needs.
#include <vector>

#include "geometry/polygon.h"
#include "scene/scene.h"

namespace bsp {

// Two vertices at the same position: dropped and counted as a repeated vertex. Narrower than eps
// (is_sliver: zero area up to the tolerance) or fewer than 3 vertices: dropped and counted as
// degenerate. Convex and planar within eps: appended as is. Otherwise (non-convex or non-planar):
// ear-clipped into triangles in the plane of its Newell normal, and counted; vertices in line with
// their neighbours are passed over, so a face with T-junction vertices loses no area.
void append_clean_polygon(Polygon&& poly, double eps, std::vector<Polygon>& out, SceneLoadStats& stats);

// Planar within eps, every turn to the same side, and winding once (a pentagram turns the same
// way at every vertex but winds twice).
bool is_convex_planar(const Polygon& poly, double eps);

// Ear clipping (Meisters' two-ears theorem; O(k^2) for k vertices) of a simple polygon, in the plane
// of its Newell normal. Vertices within eps of the line through their neighbours are removed
// without a triangle. A polygon that is not simple in projection has no ear at some step; then the
// most convex vertex is clipped regardless, so the result always covers the polygon's outline.
std::vector<Polygon> ear_clip(const Polygon& poly, double eps);

}  // namespace bsp
