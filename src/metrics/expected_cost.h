#pragma once
// Naylor's expected costs of a tree ("Constructing good partitioning trees", Graphics Interface
// 1993 [Naylor1993]), computed exactly from the cells of the tree.
//
// Cells. The root cell R is the box tree.bounds.enlarged(margin) (vec3.h: grown by margin times the
// box diagonal on every side), so cells touching the scene's extremes keep a volume. A node's cell
// is its parent's cell clipped to the front (front child) or back (back child) half-space of the
// parent's plane. In a strict tree a missing child (kNull) is a cell too, an empty one.
//
// E_point: the expected number of plane tests to locate a point drawn uniformly from R, walking
// from the root and testing the plane of every node reached. A point reaches node v iff it lies in
// cell(v), so
//     E_point = sum over nodes v with a plane of Vol(cell(v)) / Vol(R)
//             = sum over terminal cells c of Vol(c) / Vol(R) * tests(c),
// where the terminal cells are the empty child slots and the coarse leaves, and tests(c) counts the
// planes on c's path: the depth of the node owning an empty slot, the depth minus one for a coarse
// leaf (which has no plane). One plane halving R gives E_point = 1.
//
// E_line: the expected number of nodes whose cell a random line meeting R crosses, for lines drawn
// from the isotropic motion-invariant line measure. By Crofton's formula (Cauchy) the measure of
// the lines meeting a convex body is proportional to its surface area, and a line meeting cell(v)
// meets R, so
//     E_line = sum over nodes v of Area(cell(v)) / Area(R).
// It is the expected number of nodes a ray-shooting walk visits along a whole line through R; each
// term is at most 1 (surface area is monotone under inclusion of convex bodies). Coarse leaves
// count: the walk visits them to test their fragments. One plane gives E_line = 1.
#include "tree/tree.h"

namespace bsp {

// With m nodes: E_point is at best about log2(m + 1) (every plane halves its cell's volume) and at
// worst about m (a chain whose planes cut slivers off, so nearly every point reaches the bottom).
// E_line is at least 1 for a non-empty tree and at most m (every cell meets nearly every line).
struct ExpectedCosts {
  double e_point = 0;
  double e_line = 0;
  double root_volume = 0;  // Vol(R)
  double root_area = 0;    // Area(R)
};

// The root cell R for a margin (see above).
Box root_cell(const Tree& tree, double margin);

// Cells are computed depth-first on an explicit stack of polytopes, each a clip of its parent's by
// one plane, so at most one pending sibling per level is alive. Throws std::invalid_argument when R
// has no volume (a flat scene with margin 0). Zero for an empty tree.
ExpectedCosts expected_costs(const Tree& tree, double margin);

// A 2D tree (segments, geometry/segment2.h): its cells are convex polygons in the plane, the
// sections of the 3D cells above (ConvexPolytope::top_section), so the same sums with E_point over
// areas and E_line over perimeters, which Crofton's formula in the plane makes the measure of the
// lines meeting a convex set [Santalo1976]. root_volume and root_area then hold R's area and perimeter.
ExpectedCosts planar_expected_costs(const Tree& tree, double margin);

}  // namespace bsp
