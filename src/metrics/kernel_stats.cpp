#include "metrics/kernel_stats.h"

#include <nlohmann/json.hpp>

namespace bsp {

nlohmann::json to_json(const ExactBuildStats& s) {
  const SnapReport& r = s.snap;
  const ExactSideCounters& c = s.sides;
  const std::uint64_t tests = c.predicates.filtered + c.predicates.exact + c.on_grid + c.on_bound;
  return {{"snap",
           {{"vertices", r.vertices.vertices},
            {"moved", r.vertices.moved},
            {"max_displacement", r.vertices.max_displacement},
            {"mean_displacement", r.vertices.mean_displacement()},
            {"polygons", r.polygons},
            {"not_polygons", r.not_polygons},
            {"kept_whole", r.kept_whole},
            {"fanned", r.fanned},
            {"fan_triangles", r.fan_triangles},
            {"flipped", r.flipped},
            {"degenerate", r.degenerate},
            {"degenerate_area", r.degenerate_area}}},
          {"predicates",
           {{"filtered", c.predicates.filtered},
            {"exact", c.predicates.exact},
            {"on_grid", c.on_grid},
            {"on_bound", c.on_bound},
            {"coplanar_by_index", c.coplanar_by_index},
            {"boxes", c.boxes},
            {"filter_rate", tests ? static_cast<double>(c.predicates.filtered) / static_cast<double>(tests) : 1.0}}},
          {"free_planes", s.free_planes},
          {"free_planes_beyond", s.free_planes_beyond},
          {"snap_seconds", s.snap_seconds},
          {"load_seconds", s.load_seconds},
          {"view_seconds", s.view_seconds}};
}

}  // namespace bsp
