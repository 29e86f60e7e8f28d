#pragma once
// Turning a face from a file into the convex planar polygons a build needs.
#include <vector>

#include "geometry/polygon.h"
#include "scene/scene.h"

namespace bsp {

// Convex and planar within eps: appended as is. Zero area (or fewer than 3 vertices): dropped and
// counted. Otherwise (non-convex or non-planar): triangulated and counted.
void append_clean_polygon(Polygon&& poly, double eps, std::vector<Polygon>& out, SceneLoadStats& stats);

bool is_convex_planar(const Polygon& poly, double eps);

}  // namespace bsp
