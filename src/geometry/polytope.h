#pragma once
// Bounded convex polytopes as lists of faces: the cells of a BSP tree. A cell is the scene box
// (enlarged by a margin so that cells touching the scene's extremes keep a volume) cut by the
// planes on the path from the root. Used by the Naylor heuristic and the expected-cost metrics
// (Naylor, "Constructing good partitioning trees", 1993: P(child) is the child's share of the
// parent cell's volume, or of its surface area for random lines by Crofton's formula).
//
// Invariant: faces are convex, planar, and ordered counter-clockwise seen from outside, so each
// face's Newell normal points out of the polytope.
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

  // The two parts on either side of a plane, measured without building them (one pass over the
  // faces, no allocation): what Naylor's cost model needs of every candidate. Vertices within eps
  // of the plane count as on it. Surface areas include the cut face on both sides.
  struct SplitMeasure {
    double front_volume = 0, back_volume = 0;
    double front_area = 0, back_area = 0;
  };
  SplitMeasure measure_split(const Plane& plane, double eps) const;

  bool empty() const { return faces_.empty(); }
  double volume() const;        // divergence theorem: (1/3) sum of area * (n . p)
  double surface_area() const;
  Box bounds() const;
  const std::vector<Polygon>& faces() const { return faces_; }

 private:
  std::vector<Polygon> faces_;
};

}  // namespace bsp
