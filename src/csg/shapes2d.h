#pragma once
// OpenSCAD 2021.01's 2D booleans, 2D and 3D hulls and polygon triangulation, computed with CGAL
// (shapes2d_cgal.cpp; this header has no CGAL types).
//
// OpenSCAD does its 2D booleans with Clipper on integers: a coordinate c becomes the integer
// (long long)(c * 2^16) (truncation toward zero; CLIPPER_SCALE = 1 << 16 in OpenSCAD 2021.01,
// clipper-utils.h), new intersection points are rounded to the nearest integer (ties away from 0),
// collinear vertices are dropped, and the results pass through Clipper's CleanPolygon (distance
// 1.415 units) before turning back into doubles c = X / 2^16. We do the same on the same grid, but
// compute the region exactly (CGAL arrangement, Epeck) and round only the result's new vertices:
// where Clipper's double-precision intersection rounds to the neighbouring grid point, or its sweep
// reorders a near-degenerate case, our vertex is one grid step (2^-16) away from Clipper's.
// Rings come out in another order and from other start vertices than Clipper's (same geometry).
// Verified against openscad 2021.01: 1140 random unions / differences / intersection chains of
// circles, squares and self-intersecting polygon()s gave exactly OpenSCAD's grid vertices.
//
// Where OpenSCAD goes through Clipper (so where a caller should call boolean2 / sanitize2):
// a union, difference or intersection with two or more children (also the implicit union of
// several children of linear_extrude, rotate_extrude, a transform, ...); every polygon() (sanitize2);
// a 2D transform with determinant <= 0 (sanitize2). Not: a lone child (copied as is), circle(),
// square(), hull() results, non-mirroring transforms.
#include <array>
#include <vector>

#include "csg/shapes.h"

namespace bsp::csg {

inline constexpr double kClipperScale = 65536.0;  // OpenSCAD 2021.01, clipper-utils.h

enum class Op2 { Union, Intersection, Difference };

// OpenSCAD's union / intersection / difference of 2D children (GeometryEvaluator.cc
// applyToChildren2D, clipper-utils.cc apply): no operand -> empty; one operand -> that operand
// unchanged (no grid); otherwise through the 2^-16 grid as above. Union: covered by any operand;
// difference: the first minus all the others; intersection: folded left to right, each step
// rounded to the grid as Clipper's is. Operands must be sanitized (openscad_shapes.h): each is
// filled by its winding number (non-zero), as Clipper's pftNonZero fills them.
Shape2 boolean2(Op2 op, const std::vector<Shape2>& operands);

// OpenSCAD's ClipperUtils::sanitize: the even-odd region of any rings (self-intersecting, any
// orientation), on the 2^-16 grid, as sanitized rings. OpenSCAD applies it to every polygon() and
// to a sanitized 2D shape after a transform with determinant <= 0 (mirror).
Shape2 sanitize2(const Shape2& shape);

// OpenSCAD's 2D hull (applyHull2D): CGAL's convex_hull_2 of all ring points, counter-clockwise,
// collinear points dropped, no grid. Fewer than 3 hull points (all collinear): empty (OpenSCAD keeps
// a degenerate 1- or 2-point outline, which has no area).
Shape2 hull2(const std::vector<Shape2>& shapes);

// OpenSCAD's Polygon2d::tessellate (Polygon2d-CGAL.cc): CGAL's constrained Delaunay triangulation
// of all rings' points and edges (Epick, same insertion order), triangles whose nesting level is odd,
// in the triangulation's face order, each counter-clockwise. Uses only the shape's own vertices
// (for sanitized shapes, whose edges do not cross), bitwise.
std::vector<Triangle2> triangulate(const Shape2& shape);

// OpenSCAD's 3D hull (cgalutils-applyops.cc applyHull): CGAL's convex_hull_3 (Epick) into a
// Polyhedron_3, its triangles in facet order, outward counter-clockwise. OpenSCAD passes every
// child PolySet's face vertices in face order (repeats included); given the points in that order
// the facet order is OpenSCAD's too (the geometry does not depend on it). Fewer than 4 points, or all
// coplanar: empty Mesh (OpenSCAD gives no object for <= 3 points and a zero-volume two-faced sheet
// for coplanar ones).
Mesh hull3(const std::vector<Vec3>& points);

}  // namespace bsp::csg
