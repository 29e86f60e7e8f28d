#pragma once
// 2D segments and lines in homogeneous coordinates [BSP2DSlides], embedded in the 3D types so that
// every heuristic, the build loop and traversal serve both dimensions with one implementation.
//
// Notation: a 2D point (x, y) is the homogeneous triple (x, y, 1) and the 3D point (x, y, 0); a 2D
// line l = (a, b, c) holds the points with a·x + b·y + c = 0. Normalised (a² + b² = 1), l is the
// Plane {n = (a, b, 0), d = c}: a vertical plane, whose signed distance at (x, y, 0) is l·(x, y, 1).
// A segment is a Polygon of two vertices at z = 0, v0 → v1. Its front is to the RIGHT of v0 → v1
// (the convention of Doom's linedefs, whose front sidedef is on the right).
#include <optional>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "geometry/polygon.h"

namespace bsp {

// The line through a and b as a plane whose front is to the right of a → b (nullopt when a = b).
std::optional<Plane> line_through(const Vec3& a, const Vec3& b);
// Whether the plane is a 2D line: its normal has no z component.
inline bool is_line(const Plane& p) { return p.n.z == 0.0; }
// A polygon of two vertices at z = 0.
bool is_segment(const Polygon& poly);
inline bool is_segment(std::span<const Vec3> points) { return points.size() == 2; }
// A 2D scene: every polygon a segment (and at least one).
bool all_segments(std::span<const Polygon> polys);
double segment_length(std::span<const Vec3> points);
// The measure a fragment carries: area for a polygon, length for a segment.
double measure(const Polygon& poly);
// A fragment too thin to keep: a segment shorter than eps, or a polygon is_sliver rejects.
bool is_thin(const Polygon& poly, double eps);

// The point where line l meets the line through a and b: x = l × l' with l' = a × b in homogeneous
// coordinates [BSP2DSlides], divided by its weight, computed in coordinates centred at a. Only for
// a segment that crosses l.
Vec3 intersect(const Plane& l, const Vec3& a, const Vec3& b);

// Splits a segment classified Spanning by a line [BSP2DSlides]: the part on v0's side is (v0, x),
// the other (x, v1), so both keep the segment's direction and front. A part shorter than eps is a
// sliver and dropped (counted, its length in dropped_area, as for polygons).
SplitKept split_segment_into(const Polygon& seg, const Plane& line, double eps, Polygon& front, Polygon& back);

// Each segment as a wall from z = 0 to `height`: the quad (v0, v1, v1 + h, v0 + h), counter-clockwise
// seen from the segment's front, so its plane is the segment's line.
std::vector<Polygon> extruded(std::span<const Polygon> segments, double height);

}  // namespace bsp
