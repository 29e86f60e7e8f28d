#pragma once
// OpenSCAD 2021.01's primitives and extrusions, reimplemented so that `bspbench csg` builds the same
// polyhedra OpenSCAD builds from a .csg file: the same vertices (same doubles: OpenSCAD's degree
// trigonometry is reproduced), the same faces in the same order and orientation, the same fragment
// and slice counts. Sources read: OpenSCAD 2021.01, primitives.cc, calc.cc, degree_trig.cc,
// GeometryEvaluator.cc (add_slice, extrudePolygon, rotatePolygon), linearextrude.cc,
// rotateextrude.cc. No CGAL here; the 2D booleans, hulls and triangulation are in shapes2d.h.
//
// Conventions:
//  - Mesh: points without duplicates (exact equality, -0 == 0), numbered in order of first use by
//    the faces, which is how OpenSCAD's OFF export (Reindexer) numbers a PolySet's vertices; faces
//    are polygons (triangles, quads, or a cap's n-gon) counter-clockwise seen from outside, in
//    OpenSCAD's PolySet order. `openscad -o x.off` of a lone primitive prints exactly this list.
//  - Shape2: a 2D region given by rings. Rule used everywhere: the region is the set of points of odd
//    crossing parity (even-odd). Every Shape2 this code and shapes2d.h return is moreover
//    *sanitized*: rings do not cross themselves or each other (they may touch at a vertex), outer
//    rings are counter-clockwise and holes clockwise, so the non-zero rule gives the same region. polygon() alone returns raw paths
//    (even-odd, any orientation, may self-intersect): pass it through shapes2d.h's sanitize2() as
//    OpenSCAD passes it through Clipper before using it.
//  - A ring's sign (OpenSCAD's Outline2d::positive) is its orientation: signed area >= 0.
//
// Where a Mesh differs from OpenSCAD's PolySet (on purpose; same geometry):
//  - OpenSCAD computes an extrusion's top cap and the walls' top ring separately (scale s against
//    1-(1-s)*n/n, twist against twist*n/n, h2 against h1+(h2-h1)*n/n), and rotate_extrude's end cap
//    by a rotation matrix against the last ring's sin/cos: these can differ in the last bit, which
//    leaves its PolySet open along that seam (its CGAL conversion snaps them together on a 2^-20
//    grid). Here the walls' last ring and the end cap use the cap's values: the Mesh is closed.
//  - Faces degenerate by repeated points (rotate_extrude of a profile touching x = 0) are dropped,
//    as OpenSCAD's conversion to a CGAL polyhedron drops them; OpenSCAD's OFF of the lone PolySet
//    still lists them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "csg/shapes.h"
#include "geometry/vec3.h"

namespace bsp::csg {

// $fn, $fs, $fa as OpenSCAD defines them (its defaults: 0, 2, 12).
struct Resolution {
  double fn = 0, fs = 2, fa = 12;
};

// OpenSCAD's degree trigonometry (degree_trig.cc): exact at multiples of 30 and 45 degrees, which is
// why its circles have exact axis points. Exposed so that rotate() and friends match OpenSCAD too.
double sin_degrees(double deg);
double cos_degrees(double deg);

// OpenSCAD's Calc::get_fragments_from_r: 3 when r < GRID_FINE (2^-20) or $fn is inf/NaN; max(3,
// (int)$fn) when $fn > 0; otherwise ceil(max(min(360/$fa, 2 pi r/$fs), 5)). No clamping of $fs/$fa
// here (primitives clamp them to 0.01 first, as OpenSCAD's instantiate does). Throws InputError
// where OpenSCAD's count is not a usable int (e.g. $fs = $fa = 0, or more than kMaxFragments).
int fragments(double r, const Resolution& res);
inline constexpr int kMaxFragments = 1 << 22;
// The most faces one primitive or extrusion may have (a 4096-fragment sphere has 8.4 million):
// beyond it the object is refused with InputError before any memory is taken for it.
inline constexpr std::uint64_t kMaxFaces = std::uint64_t{1} << 24;

// OpenSCAD's Calc::get_helix_slices, get_conical_helix_slices and get_diagonal_slices (calc.cc).
int helix_slices(double r_sqr, double height, double twist, const Resolution& res);
int conical_helix_slices(double r_sqr, double height, double twist, double scale, const Resolution& res);
int diagonal_slices(double delta_sqr, double height, const Resolution& res);


// Numbers the points of a face list as OpenSCAD's OFF export does (first use, exact equality), after
// dropping repeated consecutive points and faces left with fewer than 3 points, as OpenSCAD does
// when it turns a PolySet into a CGAL polyhedron (cgalutils-polyhedron.cc). Every Mesh here is
// made by it; the OFF of an OpenSCAD PolySet without such degenerate faces is exactly this list.
Mesh indexed(const std::vector<std::vector<Vec3>>& faces);

// Sizes and radii that OpenSCAD refuses (<= 0, inf, NaN) give an empty Mesh / Shape2, as OpenSCAD
// gives an empty PolySet / Polygon2d (with a warning).
Mesh cube(const Vec3& size, bool center);
Mesh sphere(double r, const Resolution& res);
Mesh cylinder(double h, double r1, double r2, bool center, const Resolution& res);  // r1 or r2 may be 0


double signed_area(const Ring& ring);     // > 0 counter-clockwise (shoelace)
double area(const Shape2& shape);         // sum of the rings' signed areas (sanitized shapes)

Shape2 circle(double r, const Resolution& res);
Shape2 square(const Vec2& size, bool center);
// OpenSCAD's polygon(points, paths): paths empty -> one path of all points (none when fewer than 3
// points); otherwise one ring per path, out-of-range indices skipped (OpenSCAD warns). The result is
// raw: OpenSCAD sanitizes it (Clipper union, even-odd fill) before any use, see sanitize2().
Shape2 polygon(const std::vector<Vec2>& points, const std::vector<std::vector<std::size_t>>& paths);

struct LinearExtrude {
  double height = 100;
  bool center = false;
  double twist = 0;
  int slices = 0;  // <= 0: OpenSCAD's default, see below
  Vec2 scale{1, 1};  // negative components count as 0 (linearextrude.cc)
  Resolution res;
};
// OpenSCAD 2021.01's default slice count (extrudePolygon): twist != 0 -> helix_slices of the
// largest |v|^2 (conical_helix_slices when the scale is uniform and not 1): at least
// max(1, ceil(|twist| / 120)); with $fn > 0 ceil(|twist| / 360 * $fn), else min(ceil(|twist| / $fa),
// ceil(path length / $fs)). No twist and scale x != y -> diagonal_slices. Otherwise 1.
// Scale [0, 0] makes an apex: no top cap, one wall triangle per edge and slice on the last slice.
// A scale with one zero folds the top onto a segment (OpenSCAD's too): that Mesh is not closed.
// `shape` must be sanitized; `cap` triangulates it with the shape's own vertices (bitwise), CCW.
// Faces: bottom cap (reversed cap) at z = h1, top cap (cap scaled and rotated by -twist) at z = h2
// unless a scale is 0, then OpenSCAD's add_slice walls, slice by slice, ring by ring.
Mesh linear_extrude(const Shape2& shape, const std::vector<Triangle2>& cap, const LinearExtrude& p);
// As above, but the top cap is `triangulate` of the transformed shape, as OpenSCAD tessellates the
// transformed top polygon anew (its diagonals can differ from the bottom's when points are
// cocircular); with shapes2d.h's triangulate() this reproduces OpenSCAD's face list.
using Triangulator = std::function<std::vector<Triangle2>(const Shape2&)>;
Mesh linear_extrude(const Shape2& shape, const Triangulator& triangulate, const LinearExtrude& p);

struct RotateExtrude {
  double angle = 360;  // (-360, 360]; anything else means 360, as in OpenSCAD's rotateextrude.cc
  Resolution res;
};
// `shape` sanitized, `cap` as for linear_extrude. Throws InputError when the shape has points on both
// sides of x = 0 (OpenSCAD: an error and no object). angle 0 or empty shape: empty Mesh.
Mesh rotate_extrude(const Shape2& shape, const std::vector<Triangle2>& cap, const RotateExtrude& p);

}  // namespace bsp::csg
