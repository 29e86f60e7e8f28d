#pragma once
// A parsed CSG program (program.h) as a postfix program of 3D set operations on closed meshes:
// what every engine evaluates, so bspbench's merges, CGAL's corefinement and Manifold all take
// the same polyhedra. Transforms are pushed down to the leaves (set operations commute with affine
// maps; a mirroring map reverses the faces), 2D subtrees are evaluated here into the shapes that
// linear_extrude and rotate_extrude sweep, and every primitive is tessellated as OpenSCAD 2021.01
// does (openscad_shapes.h).
//
// Semantics follow OpenSCAD: `group`, `union`, `render`, `color`, `multmatrix` and several
// top-level objects are unions of their children; `difference` takes its first child minus the
// others; a '%' or '*' subtree is not rendered; the first '!' subtree is the whole program, without
// its ancestors' transforms; a child of the wrong dimension (2D under a 3D operation or the reverse)
// is ignored and counted, as OpenSCAD ignores it with a warning. Nodes OpenSCAD evaluates by means
// bspbench does not have (text, surface, offset, minkowski, projection, resize, 2D imports) are
// refused: InputError "FILE:LINE: problem naming the node".
#include <cstdint>
#include <string>
#include <vector>

#include "csg/program.h"
#include "geometry/polygon.h"
#include "solid/set_program.h"

namespace bsp::csg {

// One primitive's closed mesh, outward-facing convex polygons in world coordinates.
struct Leaf {
  std::vector<Polygon> polygons;
  std::uint32_t node = 0;  // in Program::nodes: the primitive (or extrusion, import, polyhedron)
};

struct LowerStats {
  std::uint64_t ignored_wrong_dimension = 0;  // 2D children of 3D operations and the reverse
  std::uint64_t not_rendered = 0;             // '%' and '*' subtrees
  std::uint64_t flipped_leaves = 0;           // leaves whose faces pointed inwards (negative volume)
  std::uint64_t cleaned_faces = 0;            // faces triangulated (non-convex or non-planar) or dropped (degenerate)
};

struct Postfix {
  std::vector<Leaf> leaves;
  std::vector<Step> steps;  // leaves a single operand: the program's solid
  LowerStats stats;

  // The leaves' polygons alone, as the proof and the CGAL peer take them.
  std::vector<std::vector<Polygon>> leaf_meshes() const;
};

// Imports are resolved relative to the program file's directory, as OpenSCAD resolves them.
Postfix lower(const Program& program);

// The name and line of a node, "sphere (line 12)", for records and messages.
std::string describe(const Program& program, std::uint32_t node);

}  // namespace bsp::csg
