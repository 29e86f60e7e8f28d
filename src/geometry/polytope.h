#pragma once
// Bounded convex polytopes as lists of faces: the cells of a BSP tree. A cell is the scene box
// (enlarged by a margin so that cells touching the scene's extremes keep a volume) cut by the
// planes on the path from the root. Used by the Naylor heuristic and the expected-cost metrics
// (Naylor, "Constructing good partitioning trees", 1993: P(child) is the child's share of the
// parent cell's volume, or of its surface area for random lines by Crofton's formula).
//
// Invariant: faces are convex, planar, and ordered counter-clockwise seen from outside, so each
// face's Newell normal points out of the polytope. Faces are spans of one array of positions, so a
// clip allocates a few arrays, not one per face.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/plane.h"
#include "geometry/polygon.h"

namespace bsp {

class ConvexPolytope {
 public:
  ConvexPolytope() = default;
  static ConvexPolytope box(const Box& b);

  // The part in front of or on the plane (distance >= 0); eps is the on-plane tolerance.
  ConvexPolytope clipped(const Plane& keep_front, double eps) const;
  // clipped() into `out` (not this one), reusing its memory: a caller clipping cell after cell
  // allocates nothing once its polytopes have grown.
  void clip_into(const Plane& keep_front, double eps, ConvexPolytope& out) const;

  // The two parts on either side of a plane, measured without building them (one pass over the
  // faces, no allocation): what Naylor's cost model needs of every candidate. Vertices within eps
  // of the plane count as on it. Surface areas include the cut face on both sides.
  struct SplitMeasure {
    double front_volume = 0, back_volume = 0;
    double front_area = 0, back_area = 0;
  };
  // What measure_split computes: volumes alone spare two square roots a face (the areas are 0).
  enum class Measures : std::uint8_t { Volumes, VolumesAndAreas };
  SplitMeasure measure_split(const Plane& plane, double eps, Measures what = Measures::VolumesAndAreas) const;

  // The cross-section of a polytope extruded from a 2D cell (a 2D tree's cells, whose planes are
  // all vertical: geometry/segment2.h): its face facing +z, whose area and perimeter are the 2D
  // cell's. Zero for a polytope without such a face.
  struct Section {
    double area = 0, perimeter = 0;
  };
  Section top_section() const;

  bool empty() const { return face_count() == 0; }
  double volume() const;        // divergence theorem: (1/3) sum of area * (n . p)
  double surface_area() const;
  Box bounds() const;
  std::size_t face_count() const { return start_.size() - 1; }
  std::span<const Vec3> face(std::size_t i) const { return {points_.data() + start_[i], start_[i + 1] - start_[i]}; }

 private:
  void add_face(std::span<const Vec3> points);

  std::vector<Vec3> points_;                                // every face's vertices, face after face
  std::vector<std::uint32_t> start_ = std::vector<std::uint32_t>(1, 0);  // face i: points_[start_[i], start_[i + 1])
};

}  // namespace bsp
