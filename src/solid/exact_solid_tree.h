#pragma once
// Solid BSP trees in the exact kernel: solid_tree.h's trees [Thibault1987] with grid planes
// (geometry/grid_plane.h) and sub-hyperplanes as plane polygons (geometry/plane_polygon.h), every
// side decided exactly, so the boundary is closed by construction: two faces meet where they share
// three planes, not where two rounded points come within a tolerance [BernsteinFussell2009].
//
// Notation as solid_tree.h: h(v) node v's plane, r(v) its region inside the space's box, shp(v) =
// h(v) ∩ r(v). Trees live in a space (ExactSolidSpace): one grid, one ± plane pool, one store of
// plane polygons; trees of one space can be merged (exact_merge.h), and share sub-hyperplanes by id.
//
// Invariants, exact (check_exact_solid below): shp(v) is h(v) ∩ r(v), a polygon of
// positive area; no node's plane is an ancestor's plane in either orientation (a strict tree puts
// every face of a plane at the first node on it, and merging removes a coplanar node where it meets
// its twin). Hence no sub-hyperplane is ever empty, and the tolerances of the float solids vanish:
// plane_eps (coplanarity is equality of pooled indices), the disagreement between the two
// classifications of partitionTree (impossible exactly: exact_merge.h), and reduce's test of a
// node whose plane misses its region (none does).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/grid.h"
#include "geometry/grid_plane_pool.h"
#include "solid/solid_tree.h"
#include "split/exact_fragments.h"
#include "tree/exact_build.h"

namespace bsp {

// A box of grid points, lo <= hi on every axis.
struct GridBox {
  GridPoint lo, hi;
};

// Where exact solid trees are built and merged. Not movable: the store refers to the pool.
class ExactSolidSpace {
 public:
  ExactSolidSpace(const Grid& grid, const GridBox& box);
  ExactSolidSpace(const ExactSolidSpace&) = delete;
  ExactSolidSpace& operator=(const ExactSolidSpace&) = delete;
  // The space of a scene box (solid_box of the operands): the grid of that box, and the box's
  // corners rounded outwards to grid points.
  static std::unique_ptr<ExactSolidSpace> for_box(const Box& box);

  const Grid& grid() const { return pool_.grid(); }
  const GridBox& box() const { return box_; }
  GridPlanePool& pool() { return pool_; }
  const GridPlanePool& pool() const { return pool_; }
  ExactFragments& shps() { return shps_; }
  const ExactFragments& shps() const { return shps_; }
  // The pooled plane of the box's face on `axis` (0, 1, 2) at its low or high end, facing inwards.
  std::uint32_t box_plane(int axis, bool high) const { return box_planes_[2 * axis + high]; }
  // A new polygon of pooled plane `plane` inside the box, or FragmentStore::kNone when the plane
  // misses the box's interior.
  std::uint32_t plane_in_box(std::uint32_t plane);
  // Keeps the part of polygon `id` in front of pooled plane `plane`: the id itself, a new part (the
  // old id released), or kNone when nothing is in front (released too). A polygon on the plane
  // (either orientation) is kept whole.
  std::uint32_t clip(std::uint32_t id, std::uint32_t plane);
  // Freed vertex runs the store reuses: a sub-hyperplane clipped by every ancestor reaches dozens
  // of vertices, more than a build's fragments.
  static constexpr std::uint32_t kReusedSpan = 256;

 private:
  GridBox box_;
  GridPlanePool pool_;
  ExactFragments shps_;
  std::uint32_t box_planes_[6] = {};
};

// 12 bytes: what a point query reads.
struct ExactSolidNode {
  std::uint32_t plane = 0;  // pooled in the space
  Ref front = kOut, back = kOut;
  Ref child(bool front_side) const { return front_side ? front : back; }
};

struct ExactSolidTree {
  std::vector<ExactSolidNode> nodes;
  std::vector<std::uint32_t> shp;  // parallel to nodes: the sub-hyperplane's id in the space's store
  Ref root = kOut;

  // Throws std::length_error past 2^31 - 2 nodes (a Ref's range; reduce marks with 2^31 - 1).
  Ref add_node(std::uint32_t plane, std::uint32_t shp_id, Ref front, Ref back);
};

// The invariants above, decided exactly, for tests and for trees a caller edited: every reachable
// node's sub-hyperplane lies on its plane (its support is the node's pooled plane), in front of or
// on every ancestor's half-space towards the node, and no ancestor has its plane in either
// orientation. Returns the first broken one as text, or an empty string.
std::string check_exact_solid(const ExactSolidTree& solid, ExactSolidSpace& space);

// A strict exact tree of a closed, outward-facing mesh as a solid tree of the space, labelled as
// solid_from_tree does (outside in front of a face, inside behind it), facing decided by pooled
// index. The tree must have been built on the space's grid (build_exact_tree's `grid`). Throws
// InputError as solid_from_tree does.
ExactSolidTree exact_solid_from_tree(const ExactTree& tree, ExactSolidSpace& space);

// The mesh's exact solid: the strict exact build by the splitter on the space's grid, then labels
// and sub-hyperplanes, each step timed.
struct ExactSolidBuild {
  ExactSolidTree solid;
  BuildStats build;
  ExactBuildStats exact;
  std::uint64_t fragments = 0;
  double label_seconds = 0;  // labelling and sub-hyperplanes
  double seconds() const { return build.build_seconds + label_seconds; }
};
ExactSolidBuild build_exact_solid(std::span<const Polygon> polys, Splitter& splitter, ExactSolidSpace& space,
                                  BuildOptions options = {});

// Where a grid point lies, exactly: a point on a node's plane goes down both sides and is On when
// their labels differ.
PointClass classify_point(const ExactSolidTree& solid, const ExactSolidSpace& space, const GridPoint& p);

SolidSize solid_size(const ExactSolidTree& solid);

// The boundary: the parts of every sub-hyperplane with IN on one side and OUT on the other, facing
// OUT, as plane polygons [Thibault1987]. Each shp(v) is pushed down v's front subtree, where the
// points just in front of it lie, then down the back subtree; a node on the same plane sends the
// piece to the side those points are on, any other cuts it exactly. Closed by construction.
std::vector<PlanePolygon> exact_solid_boundary(const ExactSolidTree& solid, ExactSolidSpace& space);

}  // namespace bsp
