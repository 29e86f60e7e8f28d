#pragma once
// A scene's polygons moved onto its grid (geometry/grid.h) and made plane polygons
// (geometry/plane_polygon.h): the exact kernel's input. What snapping changed is counted.
//
// Rules, in order, for each input polygon (source index = its index in the input):
//  - a polygon of fewer than three vertices (a 2D scene's segment) is not for the 3D exact kernel:
//    counted as `not_polygons` and left out;
//  - each vertex snaps to the nearest grid point (SnapStats: how far each moved);
//  - if the snapped points, without repeats and collinear middle points, are a convex planar
//    polygon, it is kept as one plane polygon: its support is the plane of its first three
//    non-collinear corners, on which every other corner lies exactly;
//  - otherwise (snapping bent a quad out of its plane, or made a corner reflex) it is fanned into
//    triangles from its first vertex, the rule the float kernel's loader applies to non-planar
//    input (tree/build_input.cpp); a triangle is planar and convex by construction, so it is kept
//    unless its corners are collinear. Where snapping made a corner reflex, a triangle of the fan
//    can face away from the polygon (its normal against the input's Newell normal): such triangles
//    are kept, so the fan's signed area is the snapped polygon's, and counted as `flipped`;
//  - a polygon none of whose pieces survive (it collapsed to a point or a line) is `degenerate`:
//    left out and counted, with its area before snapping.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/grid.h"
#include "geometry/plane_polygon.h"
#include "geometry/polygon.h"

namespace bsp {

// Best case: every polygon kept whole (kept == polygons, nothing fanned or degenerate).
struct SnapReport {
  SnapStats vertices;
  std::uint64_t polygons = 0;        // input polygons with three vertices or more
  std::uint64_t not_polygons = 0;    // inputs of fewer than three vertices, left out
  std::uint64_t kept_whole = 0;      // one plane polygon each
  std::uint64_t fanned = 0;          // no longer convex and planar after snapping: fanned into triangles
  std::uint64_t fan_triangles = 0;   // the plane polygons those gave
  std::uint64_t flipped = 0;         // fan triangles facing away from their input polygon
  std::uint64_t degenerate = 0;      // collapsed to a point or a line: left out
  double degenerate_area = 0.0;      // their area before snapping
};

struct SnappedScene {
  Grid grid;
  std::vector<PlanePolygon> polygons;
  std::vector<std::vector<GridPoint>> corners;  // parallel to polygons: their vertices, in order
  SnapReport report;
};

// The grid of the input's bounding box and the input on it. Throws std::domain_error for a
// non-finite coordinate (the mesh readers refuse those first).
SnappedScene snap_polygons(std::span<const Polygon> input);
// The input on a given grid (operands merged together must share one): throws std::domain_error for
// a non-finite coordinate or one beyond the grid's range.
SnappedScene snap_polygons(std::span<const Polygon> input, const Grid& grid);

}  // namespace bsp
