#pragma once
// Ground truth for solids and set operations from CGAL's exact predicates and its corefinement
// [CGAL PMP; Loriot2019]: no CGAL type crosses this header, so only exact_solid.cpp pays CGAL's
// compile time.
#include <cstdint>
#include <memory>
#include <span>

#include "geometry/polygon.h"
#include "solid/merge.h"

namespace bsp {

enum class ExactSide : std::uint8_t { Outside, Inside, Boundary };

// One closed operand as a CGAL triangle mesh (convex faces fanned, vertices shared by exact
// coordinates) with the structures its queries need.
class ExactSolid {
 public:
  explicit ExactSolid(std::span<const Polygon> polys);
  ExactSolid(const ExactSolid&);
  ExactSolid& operator=(const ExactSolid&) = delete;
  ~ExactSolid();

  // Side_of_triangle_mesh with exact predicates.
  ExactSide side(const Vec3& p) const;
  double distance(const Vec3& p) const;  // to the surface (AABB tree; rounded constructions)
  double volume() const;
  std::size_t triangles() const;
  // Pairs of triangles that intersect other than along a shared edge or vertex (exact predicates).
  // A surface with any is not the boundary of a solid: its faces' facing and its signed volume
  // disagree about what is inside.
  std::size_t self_intersecting_pairs() const;

 private:
  friend struct CorefineAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// PMP::corefine_and_compute_{union,intersection,difference} of copies of the operands (the
// symmetric difference as the union of both differences). Throws std::runtime_error when CGAL
// reports failure (self-intersecting input).
struct CorefineResult {
  double volume = 0;
  std::size_t triangles = 0;
};
CorefineResult corefine(const ExactSolid& a, const ExactSolid& b, SetOp op);

// The same operation with CGAL's Nef polyhedra (exact constructions; exact_nef.cpp): both meshes
// converted to Nef polyhedra, then combined. Returns the seconds it took, conversions included, and
// the result's volume (its boundary as a triangle mesh, measured exactly).
struct NefResult {
  double seconds = 0;
  double volume = 0;
};
NefResult nef_set_operation(std::span<const Polygon> a, std::span<const Polygon> b, SetOp op);

}  // namespace bsp
