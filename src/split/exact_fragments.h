#pragma once
// The fragments of an exact-kernel build: plane polygons (geometry/plane_polygon.h) whose every
// side is decided exactly, each with a rounded copy in a FragmentStore under the same id for what
// splitters estimate from geometry (areas, centroids, the points halving looks at). The copy
// never decides a side: a splitter that counts sides gets the exact counts (SideCounter reads
// SplitContext::exact), and the build partitions with classify() and split() here.
//
// A fragment is first tested whole, against a box in grid coordinates that contains its exact
// vertices (FilterBox): most fragments lie clear of a plane, as in the float kernel's bounding-sphere
// test (`boxes` counts those decided so). Otherwise each vertex is tested, cheapest way first:
//  - the filter on the vertex's cached cofactors (geometry/exact_predicates.h: VertexCofactors);
//  - an input corner (a vertex made by two bounds of its input polygon, so a grid point): the
//    plane's value there in 128-bit integers, exact by grid_plane.h's bounds (`on_grid`);
//  - otherwise the 4x4 determinant in wide integers (`exact`).
// A fragment whose support is the plane, in either orientation, is coplanar without a test: pooled
// planes are canonical, so equal planes have equal indices.
//
// Ids and their reuse are the copy's (FragmentStore), so both stores agree on every id. Nothing is
// ever dropped: a split's parts have positive area by the plane polygons' invariants.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/grid_plane_pool.h"
#include "geometry/plane_polygon.h"
#include "split/fragment_store.h"

namespace bsp {

// How the side tests of a build were decided (best: all filtered).
struct ExactSideCounters {
  PredicateCounters predicates;  // filtered, and decided in wide integers
  std::uint64_t on_grid = 0;     // decided at an input corner in 128-bit integers
  std::uint64_t coplanar_by_index = 0;  // fragments found coplanar by their pooled support
  std::uint64_t boxes = 0;              // fragments decided whole by their box
};

class ExactFragments {
 public:
  explicit ExactFragments(GridPlanePool& planes) : planes_(planes) {}

  // Pools the polygon's support; `corners` says which of its vertices are grid points (input
  // corners), given in vertex order, or is empty when none is known.
  std::uint32_t add(PlanePolygon poly, std::span<const GridPoint> corners = {});
  void release(std::uint32_t id);
  // The fragment's plane polygon, moved out; the fragment is released.
  PlanePolygon take(std::uint32_t id);

  const PlanePolygon& polygon(std::uint32_t id) const { return poly_[id]; }
  std::uint32_t plane(std::uint32_t id) const { return rounded_.plane(id); }  // pooled support
  const FragmentStore& rounded() const { return rounded_; }
  GridPlanePool& planes() const { return planes_; }

  // The fragment's side of pooled plane `plane`, exactly.
  Side classify(std::uint32_t id, std::uint32_t plane) const;
  // Counts of ids on each side of each plane, added to out[j] for planes[j] (SideCounts).
  void count_sides(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                   std::span<SideCounts> out) const;
  // Splits a fragment classified Spanning by pooled plane `plane` and releases it; the parts keep
  // its support and source. Both parts exist (nothing is a sliver in the exact kernel).
  struct Parts {
    std::uint32_t front = FragmentStore::kNone, back = FragmentStore::kNone;
  };
  Parts split(std::uint32_t id, std::uint32_t plane);

  const ExactSideCounters& counters() const { return counters_; }

 private:
  struct Vertex {
    VertexCofactors cofactors;
    GridPoint corner;
    bool on_grid = false;
  };

  // Side of vertex i of fragment id: +1, -1 or 0.
  int vertex_side(std::uint32_t id, std::size_t i, const GridPlane& plane, const PlaneApprox& approx) const;
  // Fills sides_ for the fragment's vertices; returns Front/Back/Coplanar/Spanning, stopping at
  // the first vertex that makes it Spanning unless `all`. vertex_sides skips the whole-fragment tests.
  Side sides(std::uint32_t id, std::uint32_t plane, bool all) const;
  Side vertex_sides(std::uint32_t id, std::uint32_t plane, const PlaneApprox& approx, bool all) const;
  void count_block(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                   std::span<SideCounts> out) const;
  std::uint32_t add_part(PolygonPart part, const std::vector<Vertex>& from);
  std::uint32_t store(PlanePolygon poly, std::vector<Vertex> verts);

  GridPlanePool& planes_;
  FragmentStore rounded_;
  std::vector<PlanePolygon> poly_;          // by id
  std::vector<std::vector<Vertex>> verts_;  // by id, parallel to poly_[id]'s vertices
  std::vector<FilterBox> box_;              // by id
  // Counts and scratch, not state: a store is used by one thread at a time.
  mutable ExactSideCounters counters_;
  mutable std::vector<int> sides_;
  std::vector<PlaneApprox> bounds_approx_;

};

}  // namespace bsp
