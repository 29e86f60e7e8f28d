#pragma once
// Building a tree in the exact kernel: the input snapped to the scene's grid (geometry/snap.h),
// fragments as plane polygons, and every side decided exactly (split/exact_fragments.h), so no
// fragment is dropped and no tie is left to a tolerance. The same splitters choose the planes: a
// fragment's plane is its exact support; a free plane is rounded to a grid plane by round_plane's
// rule (geometry/grid_plane.h); sides a splitter counts are counted exactly.
//
// Tolerances: none decides anything here. Of the float kernel's, plane_eps (sides and slivers),
// kParallelCosineSlack and the boundary weld have no counterpart, since a side is a determinant's
// sign and coplanarity is equality of canonical planes. Splitters still receive Tolerance for the
// estimates some of them compute from the rounded copies (naylor's cell measures, halving's
// grouping of normals): those steer a choice, never a side, and a free plane they produce is
// rounded like any other.
//
// One thread; shapes strict and coarse (a coarse leaf's convexity is decided exactly too).
// Deterministic: the same input, splitter settings and seed give the same tree, bit for bit.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/grid_plane.h"
#include "geometry/plane_polygon.h"
#include "geometry/plane_polygon_set.h"
#include "geometry/snap.h"
#include "split/exact_fragments.h"
#include "split/splitter.h"
#include "tree/build_options.h"
#include "tree/tree.h"

namespace bsp {

// Which geometry a build uses: doubles with the tolerance plane_eps (tree/build.h), or this file's.
enum class Kernel : std::uint8_t { Float, Exact };
// "float", "exact": the names the CLI and every JSON use.
const char* kernel_name(Kernel k);
std::optional<Kernel> kernel_named(std::string_view name);

// What the exact build did that a float build has no counter for. Best case: every side test
// filtered, nothing fanned, no free plane beyond the grid.
struct ExactBuildStats {
  SnapReport snap;
  ExactSideCounters sides;
  std::uint64_t free_planes = 0;         // free planes rounded to grid planes
  std::uint64_t free_planes_beyond = 0;  // free planes that missed the grid (the node fell back)
  // Where build_seconds went besides choosing (BuildStats::choose_seconds): snapping the input,
  // loading it (vertex cofactors, pooling the supports), and the rest of the build loop and freezing.
  double snap_seconds = 0.0;
  double load_seconds = 0.0;
  double view_seconds = 0.0;  // computing the view's vertices (not in build_seconds)
};

struct ExactTree {
  // The view of the tree in doubles, for output and for the measures that read a Tree: nodes as
  // built, scene planes rounded from the grid planes, fragments with vertices computed from their
  // planes (vertex_position). stats as a float build's, with dropped_slivers and dropped_area of
  // the build itself always 0 (dropped_input counts the inputs snapping collapsed or that are not
  // polygons; triangulated_extra the triangles fanning added).
  Tree tree;
  Grid grid = Grid::for_box(Box{});
  std::vector<GridPlane> planes;        // by pair: tree.planes[2k] is the rounding of planes[k]
  PlanePolygonSet fragments;            // parallel to tree.fragments
  ExactBuildStats exact;

  GridPlane plane(std::uint32_t i) const { return (i & 1u) ? -planes[i >> 1] : planes[i >> 1]; }
};

// Throws std::invalid_argument for an incremental or leafy build, which the exact kernel does not
// make, and std::domain_error for a non-finite coordinate. The input is snapped to `grid` when given
// (operands to be merged share one), else to the grid of its own box.
ExactTree build_exact_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options = {},
                           const Grid* grid = nullptr);

}  // namespace bsp
