#include "validate/exact_solid_check.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/rng.h"
#include "geometry/snap.h"
#include "validate/exact_solid.h"

namespace bsp {

namespace {

Vec3 as_vec(const GridPoint& q) { return {static_cast<double>(q.x), static_cast<double>(q.y), static_cast<double>(q.z)}; }

GridPoint nearest(const Vec3& p) { return {std::llround(p.x), std::llround(p.y), std::llround(p.z)}; }

std::vector<std::vector<GridPoint>> snapped_corners(std::span<const Polygon> polys, const Grid& grid) {
  return snap_polygons(polys, grid).corners;
}

// A grid point near a random face: near_surface_point rounded to the grid.
GridPoint near_surface(std::span<const Polygon> faces, Rng& rng, double reach) {
  return nearest(near_surface_point(faces, rng, reach));
}

}  // namespace

std::vector<Polygon> grid_unit_polygons(std::span<const Polygon> polys, const Grid& grid) {
  std::vector<Polygon> out;
  for (const auto& corners : snapped_corners(polys, grid)) {
    Polygon p;
    for (const GridPoint& q : corners) p.verts.push_back({as_vec(q)});
    out.push_back(std::move(p));
  }
  return out;
}

void require_snapped_solid(std::span<const Polygon> polys, const Grid& grid, const std::string& name) {
  const std::vector<Polygon> snapped = grid_unit_polygons(polys, grid);
  require_closed_solid(snapped, 0.0, name + " (snapped to the grid)");
  if (const std::size_t n = ExactSolid(snapped).self_intersecting_pairs(); n > 0)
    throw InputError(name + ": not the boundary of a solid after snapping to the grid: " + std::to_string(n) +
                     " pairs of faces intersect");
}

ExactSolidCheck check_exact_set_operation(const ExactSolidTree& result, const ExactSolidSpace& space,
                                          std::span<const PlanePolygon> boundary, std::span<const Polygon> a,
                                          std::span<const Polygon> b, SetOp op, const SolidCheckSettings& settings) {
  ExactSolidCheck c;
  const std::vector<Polygon> ga = grid_unit_polygons(a, space.grid()), gb = grid_unit_polygons(b, space.grid());
  const ExactSolid ea(ga), eb(gb);
  Box box;
  for (const auto* polys : {&ga, &gb})
    for (const Polygon& p : *polys)
      for (const Vertex& v : p.verts) box.add(v.p);
  const double reach = settings.near_distance * box.diagonal();
  Rng rng(stream_seed(settings.seed, 0xe5011d));
  for (std::uint64_t i = 0; i < settings.points; ++i) {
    const GridPoint q = i % 2 == 0 ? nearest({rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y),
                                              rng.uniform(box.lo.z, box.hi.z)})
                                   : near_surface(i % 4 == 1 ? ga : gb, rng, reach);
    ++c.points;
    const ExactSide sa = ea.side(as_vec(q)), sb = eb.side(as_vec(q));
    if (sa == ExactSide::Boundary || sb == ExactSide::Boundary) {
      ++c.on_operand;
      continue;
    }
    ++c.compared;
    const bool truth = in_result(op, sa == ExactSide::Inside, sb == ExactSide::Inside);
    c.mismatches += classify_point(result, space, q) != (truth ? PointClass::In : PointClass::Out);
  }
  c.boundary = check_exact_boundary(boundary);
  const double step = space.grid().step();
  c.volume = c.boundary.volume_double * step * step * step;
  try {
    const ExactCorefine r = exact_corefine(snapped_corners(a, space.grid()), snapped_corners(b, space.grid()), op);
    c.corefine_volume = r.volume;
    c.corefine_volume_scene = r.volume_double * step * step * step;
    c.corefine_seconds = r.seconds;
  } catch (const std::runtime_error& e) {
    c.corefine_error = e.what();
  }
  return c;
}

nlohmann::json to_json(const ExactSolidCheck& c) {
  return {{"points", c.points},
          {"on_operand_surface", c.on_operand},
          {"within_plane_eps", 0},
          {"within_plane_eps_disagree", 0},
          {"compared", c.compared},
          {"mismatches", c.mismatches},
          {"tree_volume", c.volume},
          {"corefine_volume", c.corefine_volume_scene},
          {"volume_exact", c.boundary.volume},
          {"corefine_volume_exact", c.corefine_volume},
          {"volume_equal", c.volume_equal()},
          {"corefine_seconds", c.corefine_seconds},
          {"corefine_error", c.corefine_error},
          {"boundary",
           {{"faces", c.boundary.faces},
            {"edges", c.boundary.edges},
            {"lines", c.boundary.lines},
            {"border_edges", c.boundary.border_segments},
            {"volume", c.volume}}},
          {"ok", c.ok()}};
}

}  // namespace bsp
