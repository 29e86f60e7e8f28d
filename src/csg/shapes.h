#pragma once
// The shapes of OpenSCAD's geometry as bspbench's CSG evaluation holds them: a polyhedron as points
// and faces, a 2D region as rings. Types only: openscad_shapes.h makes them as OpenSCAD does,
// shapes2d.h combines them with CGAL. Conventions (which rings bound a region, which way faces
// turn) are stated in openscad_shapes.h.
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/vec3.h"

namespace bsp::csg {

struct Mesh {
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;  // outward CCW, indices into points, OpenSCAD's order
};

struct Vec2 {
  double x = 0, y = 0;
  constexpr bool operator==(const Vec2&) const = default;
};
struct Ring {
  std::vector<Vec2> points;  // closed, the last point not repeated
};
struct Shape2 {
  std::vector<Ring> rings;  // the rule is in openscad_shapes.h
  bool empty() const { return rings.empty(); }
};
using Triangle2 = std::array<Vec2, 3>;  // counter-clockwise

}  // namespace bsp::csg
