#include "geometry/snap.h"

#include <stdexcept>
#include <utility>

namespace bsp {

namespace {

Grid grid_of(std::span<const Polygon> input) {
  Box box;
  for (const Polygon& poly : input)
    for (const Vertex& v : poly.verts) {
      if (!is_finite(v.p)) throw std::domain_error("a vertex has a non-finite coordinate");
      box.add(v.p);
    }
  return Grid::for_box(box);
}

// The fan from the first point: the triangles that are not collinear, with their vertices.
std::vector<std::pair<PlanePolygon, std::vector<GridPoint>>> fan(const std::vector<GridPoint>& points,
                                                                 std::uint32_t source) {
  std::vector<std::pair<PlanePolygon, std::vector<GridPoint>>> out;
  std::vector<GridPoint> vertices;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const GridPoint triangle[] = {points[0], points[i], points[i + 1]};
    if (auto t = plane_polygon(triangle, source, &vertices)) out.emplace_back(std::move(*t), vertices);
  }
  return out;
}

}  // namespace

SnappedScene snap_polygons(std::span<const Polygon> input) { return snap_polygons(input, grid_of(input)); }

SnappedScene snap_polygons(std::span<const Polygon> input, const Grid& grid) {
  SnappedScene out{grid, {}, {}, {}};
  SnapReport& r = out.report;
  std::vector<GridPoint> points, vertices;
  out.polygons.reserve(input.size());
  out.corners.reserve(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Polygon& poly = input[i];
    if (poly.verts.size() < 3) {
      ++r.not_polygons;
      continue;
    }
    ++r.polygons;
    points.clear();
    for (const Vertex& v : poly.verts) {
      if (!is_finite(v.p)) throw std::domain_error("a vertex has a non-finite coordinate");
      const auto snapped = out.grid.snap(v.p);
      if (!snapped) throw std::domain_error("a vertex lies beyond the grid's range");
      const GridPoint q = *snapped;
      r.vertices.add(length(out.grid.point(q) - v.p));
      points.push_back(q);
    }
    const auto source = static_cast<std::uint32_t>(i);
    if (auto whole = plane_polygon(points, source, &vertices)) {
      ++r.kept_whole;
      out.polygons.push_back(std::move(*whole));
      out.corners.push_back(vertices);
      continue;
    }
    auto triangles = fan(points, source);
    if (triangles.empty()) {
      ++r.degenerate;
      r.degenerate_area += area(poly);
      continue;
    }
    ++r.fanned;
    r.fan_triangles += triangles.size();
    const Vec3 facing = newell_normal(poly);
    for (auto& [t, corners] : triangles) {
      const Vec3 n{static_cast<double>(t.support.a), static_cast<double>(t.support.b), static_cast<double>(t.support.c)};
      r.flipped += dot(n, facing) < 0;
      out.polygons.push_back(std::move(t));
      out.corners.push_back(std::move(corners));
    }
  }
  return out;
}

}  // namespace bsp
