#pragma once
// Exact measures of the exact kernel's solids, in grid coordinates (geometry/grid.h: units are grid
// steps, so no rounding of scene coordinates enters): whether a set of faces closes, the volume it
// encloses, and CGAL's corefinement of two meshes measured exactly [CGALPMP]. Volumes are rationals
// given as canonical text, "p/q" in lowest terms with q > 0, or "p" when q == 1, so equal volumes
// give equal strings and a test compares them as strings. No GMP or CGAL type crosses this header.
//
// Cost: the numbers are exact, so their size grows with the input's. A vertex made by three
// planes has coordinates with numerators below 2^295 and a denominator below 2^252; a volume sums
// such rationals, and when many vertices have distinct denominators the sum's denominator can grow
// to thousands of bits (the sum is exact, not fast). Faces whose vertices are all grid points cost
// integer arithmetic only.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "geometry/grid.h"
#include "geometry/plane_polygon.h"
#include "geometry/polygon.h"
#include "solid/merge.h"
#include "solid/set_program.h"

namespace bsp {

struct ExactBoundaryCheck {
  std::uint64_t faces = 0, edges = 0;  // faces given, their edges
  std::uint64_t vertices = 0;          // distinct vertices (equal exact coordinates are one vertex)
  std::uint64_t lines = 0;             // distinct supporting lines of edges
  // Maximal pieces of a line where the signed edge coverage is not zero: where the boundary of
  // the faces' boundary is not empty. A piece runs from where the coverage leaves zero to where
  // it returns to zero (a change from +1 to -1 inside it does not end it).
  std::uint64_t border_segments = 0;
  std::string volume;        // enclosed volume in grid units^3 (divergence theorem), canonical text
  double volume_double = 0;  // the same, truncated toward zero (within one unit in the last place)
  bool closed() const { return border_segments == 0; }
};

// Faces oriented outward (the support's front is outside), each a valid plane polygon (is_valid),
// with the grid planes' bounds (geometry/grid_plane.h: |a|, |b|, |c| < 2^83, |d| < 2^125; checked,
// std::invalid_argument otherwise, as is a vertex whose three planes do not meet in a point).
// Exact throughout: vertices are rationals (Cramer's rule), and closure is decided on every edge's
// supporting line: an edge from P to Q adds the coverage +1 (along the line's direction) or -1
// (against it) over PQ, and the faces are closed when every line's coverage is zero everywhere
// (the boundary of the boundary is empty). Edges need not match one to one: a T-junction, where
// one face's edge is covered by two edges of others, is closed.
ExactBoundaryCheck check_exact_boundary(std::span<const PlanePolygon> faces);

// The exact volume of one closed mesh of grid-point polygons, each convex (fanned from its first
// point), oriented outward (counter-clockwise seen from outside), coordinates below 2^kGridBits
// in magnitude (std::invalid_argument otherwise). Integer arithmetic, no CGAL: six times the
// volume is a sum of integer determinants.
std::string exact_mesh_volume(std::span<const std::vector<GridPoint>> polys);

// PMP::corefine_and_compute_{union,intersection,difference} [CGALPMP] with exact constructions
// (CGAL's Epeck) on two closed meshes of grid-point polygons as above (convex polygons fanned into
// triangles, vertices shared by equal coordinates); the symmetric difference is the union of both
// differences, as `corefine` in validate/exact_solid.h. The result's volume is PMP::volume made
// exact. Throws std::runtime_error when an operand is not a closed polygon mesh or CGAL reports
// failure (self-intersecting operands).
struct ExactCorefine {
  std::string volume;        // canonical text, grid units^3
  double volume_double = 0;  // the same, truncated toward zero
  double seconds = 0;        // wall time: both meshes built, the operation, the volume
  std::size_t triangles = 0;
};
ExactCorefine exact_corefine(std::span<const std::vector<GridPoint>> a, std::span<const std::vector<GridPoint>> b,
                             SetOp op);

// A program of set operations (solid/set_program.h) evaluated by CGAL's corefinement step by step
// with exact constructions, each step's result meshed and passed on, as a user of CGAL combines a
// CSG program: the reference volume of bspbench csg, and the CGAL peer of the csg runs. Leaves are
// closed outward meshes of convex polygons whose coordinates are doubles taken exactly (grid units
// for the exact kernel). A hull step is CGAL's convex_hull_3 of its operands' vertices; an empty
// operand is kept as such (a union ignores it, an intersection becomes empty). CGAL's failure is
// reported in `error`, not thrown: a peer that fails is a result. FoldOrder::Balanced combines the
// operands of each step as a balanced tree instead (a union or intersection pairwise in rounds; a
// difference as the first minus the balanced union of the others): the same solid at O(n log n)
// corefinements of growing meshes instead of O(n^2), for a reference where the order is not the
// point (a plate drilled 1000 times).
struct ExactProgramVolume {
  std::string volume;        // canonical text (cubed units of the leaves' coordinates); empty on error
  double volume_double = 0;  // the same, truncated toward zero
  double seconds = 0;        // wall time: leaves meshed, every step, the volume
  std::uint64_t operations = 0;  // binary corefinements and hulls done
  std::size_t triangles = 0;     // of the final mesh
  std::string error;
};
enum class FoldOrder : std::uint8_t { LeftToRight, Balanced };
// `hulls`, when given, are the hull steps' results in order (one mesh each, empty for none): a proof
// takes the evaluator's hulls as it takes its leaves, so both measure the same polyhedra.
ExactProgramVolume exact_corefine_program(std::span<const std::vector<Polygon>> leaves, std::span<const Step> steps,
                                          FoldOrder order = FoldOrder::LeftToRight,
                                          const std::vector<std::vector<Polygon>>* hulls = nullptr);

// The same program with CGAL's Nef polyhedra (exact_nef.cpp), which, unlike corefinement, accept
// the non-manifold solids a program can make (two parts touching along an edge or at a vertex) as
// operands of the next step: the reference where corefinement refuses an intermediate result.
ExactProgramVolume exact_nef_program(std::span<const std::vector<Polygon>> leaves, std::span<const Step> steps,
                                     FoldOrder order = FoldOrder::LeftToRight,
                                     const std::vector<std::vector<Polygon>>* hulls = nullptr);

}  // namespace bsp
