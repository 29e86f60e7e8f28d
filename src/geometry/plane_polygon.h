#pragma once
// A convex polygon of the exact kernel, as planes [Sugihara1989] [BernsteinFussell2009]: the part of
// its support plane in front of every one of its bounding planes. No vertex is stored; vertex i is
// where the support, bounds[i] and bounds[i + 1] meet (indices modulo the bound count), and edge i
// lies on bounds[i], from vertex i - 1 to vertex i. Splitting by a plane only adds that plane as a
// bound of each part, so a split never rounds a number and the parts share their new vertices
// exactly (the same three planes).
//
// Invariants (checked by is_valid): at least three bounds; every vertex is defined (its three planes
// meet in one point) with the bounds in counter-clockwise order (det of the normals of the support,
// bounds[i] and bounds[i + 1] positive), and lies strictly in front of every bound it is not on, so
// no edge has zero length and no bound is redundant.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/exact_predicates.h"
#include "geometry/grid_plane.h"
#include "geometry/polygon.h"

namespace bsp {

struct PlanePolygon {
  GridPlane support;
  std::vector<GridPlane> bounds;  // counter-clockwise seen from the support's front
  std::uint32_t source = 0;

  std::size_t size() const { return bounds.size(); }
  // The planes that meet in vertex i.
  const GridPlane& before(std::size_t i) const { return bounds[i]; }
  const GridPlane& after(std::size_t i) const { return bounds[(i + 1) % bounds.size()]; }
};

// The polygon of grid points given counter-clockwise, convex and coplanar (every point on the plane
// of the first three non-collinear ones). Points equal to the one before and points collinear with
// their neighbours are left out, since they bound nothing (so is the tip of a spike that doubles
// back along an edge: its two sides are collinear, and the polygon without it has the same area). nullopt when fewer than three points
// remain, or when the points are not coplanar or not strictly convex.
// When `vertices` is given, it receives the polygon's vertices as grid points, in vertex order.
std::optional<PlanePolygon> plane_polygon(std::span<const GridPoint> points, std::uint32_t source,
                                          std::vector<GridPoint>* vertices = nullptr);

// The side of each vertex of `poly` with respect to `plane`: +1, -1 or 0.
std::vector<int> vertex_sides(const PlanePolygon& poly, const GridPlane& plane, PredicateCounters& counters);

struct PlaneSplit {
  Side side = Side::Coplanar;
  std::optional<PlanePolygon> front, back;  // set only when side is Spanning
};

// One part of a split polygon, with where its vertices come from: vertex i of `poly` is vertex
// origin[i] of the polygon split, or kNewVertex where the cut meets an edge (the last two).
inline constexpr std::uint32_t kNewVertex = 0xffffffffu;
struct PolygonPart {
  PlanePolygon poly;
  std::vector<std::uint32_t> origin;
};
// The part of `poly` on side `keep` (+1 or -1) of `cut`, bounded by `cut` (keep = +1) or its
// opposite (keep = -1), given the vertices' sides (vertex_sides), which must include both signs.
PolygonPart part_of(const PlanePolygon& poly, std::span<const int> sides, int keep, const GridPlane& cut);
// The edges part_of keeps, as indices of the polygon's bounds in the part's order (the cut follows
// them): a consecutive run, so the part's vertex i before the last two is the polygon's vertex
// out[i]. For callers that keep polygons in their own arrays; `out` is cleared first.
void kept_edges(std::span<const int> sides, int keep, std::vector<std::uint32_t>& out);

// Classifies `poly` against `plane`, exactly: Front when no vertex is behind it (and one is in front),
// Back likewise, Coplanar when every vertex is on it, else Spanning with both parts: the front part
// bounded by the plane, the back part by its opposite.
PlaneSplit split(const PlanePolygon& poly, const GridPlane& plane, PredicateCounters& counters);

// The invariants above, decided exactly.
bool is_valid(const PlanePolygon& poly, PredicateCounters& counters);

// The vertices in scene coordinates, for output only (geometry/exact_predicates.h: vertex_position).
std::vector<Vec3> vertex_positions(const PlanePolygon& poly, const Grid& grid);

}  // namespace bsp
