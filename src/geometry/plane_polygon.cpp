#include "geometry/plane_polygon.h"

namespace bsp {

namespace {

// (q - p) x (r - p) == 0, exactly (components below 2^83).
bool collinear(const GridPoint& p, const GridPoint& q, const GridPoint& r) {
  const Int128 ex = Int128{q.x} - p.x, ey = Int128{q.y} - p.y, ez = Int128{q.z} - p.z;
  const Int128 fx = Int128{r.x} - p.x, fy = Int128{r.y} - p.y, fz = Int128{r.z} - p.z;
  return ey * fz == ez * fy && ez * fx == ex * fz && ex * fy == ey * fx;
}

// The points without repeats and without points collinear with their neighbours (cyclically).
std::vector<GridPoint> corners(std::span<const GridPoint> points) {
  std::vector<GridPoint> out(points.begin(), points.end());
  for (bool changed = true; changed && out.size() >= 3;) {
    changed = false;
    for (std::size_t i = 0; i < out.size() && out.size() >= 3; ++i) {
      const GridPoint& prev = out[(i + out.size() - 1) % out.size()];
      const GridPoint& next = out[(i + 1) % out.size()];
      if (out[i] == prev || collinear(prev, out[i], next)) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  return out;
}

}  // namespace

std::optional<PlanePolygon> plane_polygon(std::span<const GridPoint> points, std::uint32_t source,
                                          std::vector<GridPoint>* vertices) {
  const std::vector<GridPoint> c = corners(points);
  if (c.size() < 3) return std::nullopt;
  const auto support = plane_through(c[0], c[1], c[2]);
  if (!support) return std::nullopt;
  PlanePolygon poly{*support, {}, source};
  const std::size_t k = c.size();
  poly.bounds.reserve(k);
  for (std::size_t i = 0; i < k; ++i) {
    if (support->side(c[i]) != 0) return std::nullopt;
    // Edge i runs from point i to point i + 1, so vertex i is point i + 1; any third corner is
    // inside a strictly convex polygon's edge plane.
    const auto edge = edge_plane(c[i], c[(i + 1) % k], *support, c[(i + 2) % k]);
    if (!edge) return std::nullopt;
    poly.bounds.push_back(*edge);
  }
  // Strictly convex: every corner in front of every edge plane it is not on.
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j)
      if (j != i && j != (i + 1) % k && poly.bounds[i].side(c[j]) <= 0) return std::nullopt;
  if (vertices) {  // vertex i, where edges i and i + 1 meet, is point i + 1
    vertices->clear();
    for (std::size_t i = 0; i < k; ++i) vertices->push_back(c[(i + 1) % k]);
  }
  return poly;
}

// The edges with an endpoint on `keep`'s side, in order. The vertices on the other side form one
// run (the polygon is convex); the walk starts at the edge leaving that run, so the kept edges are
// consecutive and the cut closes the part where the run was.
void kept_edges(std::span<const int> sides, int keep, std::vector<std::uint32_t>& out) {
  const std::size_t k = sides.size();
  out.clear();
  std::size_t run_end = 0;  // both signs occur, so the other side's run has an end
  while (!(sides[run_end] == -keep && sides[(run_end + 1) % k] != -keep)) ++run_end;
  for (std::size_t n = 1; n <= k; ++n) {
    const std::size_t j = (run_end + n) % k;  // edge j runs from vertex j - 1 to vertex j
    if (sides[(j + k - 1) % k] != keep && sides[j] != keep) continue;
    out.push_back(static_cast<std::uint32_t>(j));
  }
}

// The kept edges' bounds, then the cut. Consecutive kept edges j - 1 and j meet in the split
// polygon's vertex j - 1; the last kept edge meets the cut, and the cut the first, in new vertices.
PolygonPart part_of(const PlanePolygon& poly, std::span<const int> sides, int keep, const GridPlane& cut) {
  const std::size_t k = poly.size();
  std::vector<std::uint32_t> kept;
  kept_edges(sides.first(k), keep, kept);
  PolygonPart out{{poly.support, {}, poly.source}, {}};
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (i > 0) out.origin.push_back(static_cast<std::uint32_t>((kept[i] + k - 1) % k));
    out.poly.bounds.push_back(poly.bounds[kept[i]]);
  }
  out.poly.bounds.push_back(keep > 0 ? cut : -cut);
  out.origin.push_back(kNewVertex);  // the last kept edge meets the cut
  out.origin.push_back(kNewVertex);  // the cut meets the first kept edge
  return out;
}

std::vector<int> vertex_sides(const PlanePolygon& poly, const GridPlane& plane, PredicateCounters& counters) {
  std::vector<int> sides(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i)
    sides[i] = side_of_vertex(poly.support, poly.before(i), poly.after(i), plane, counters);
  return sides;
}

PlaneSplit split(const PlanePolygon& poly, const GridPlane& plane, PredicateCounters& counters) {
  const std::vector<int> sides = vertex_sides(poly, plane, counters);
  bool front = false, back = false;
  for (int s : sides) {
    front |= s > 0;
    back |= s < 0;
  }
  if (!front && !back) return {Side::Coplanar, {}, {}};
  if (!back) return {Side::Front, {}, {}};
  if (!front) return {Side::Back, {}, {}};
  return {Side::Spanning, part_of(poly, sides, 1, plane).poly, part_of(poly, sides, -1, plane).poly};
}

bool is_valid(const PlanePolygon& poly, PredicateCounters& counters) {
  const std::size_t k = poly.size();
  if (k < 3) return false;
  for (std::size_t i = 0; i < k; ++i) {
    // Defined, and counter-clockwise: the normals of the support and of consecutive bounds turn
    // the same way at every vertex (for a square in z = 0 seen from +z: +z, +y, -x, det = +1).
    if (normals_sign(poly.support, poly.before(i), poly.after(i), counters) <= 0) return false;
    for (std::size_t j = 0; j < k; ++j) {
      if (j == i || j == (i + 1) % k) continue;
      if (side_of_vertex(poly.support, poly.before(i), poly.after(i), poly.bounds[j], counters) <= 0) return false;
    }
  }
  return true;
}

std::vector<Vec3> vertex_positions(const PlanePolygon& poly, const Grid& grid) {
  std::vector<Vec3> out;
  out.reserve(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i)
    if (auto p = vertex_position(poly.support, poly.before(i), poly.after(i), grid)) out.push_back(*p);
  return out;
}

}  // namespace bsp
