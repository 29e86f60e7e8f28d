#include "sweep/run_merge_job.h"

#include <chrono>
#include <nlohmann/json.hpp>

#include "catalog.h"
#include "solid/boundary.h"
#include "solid/solid_build.h"
#include "split/registry.h"
#include "sweep/calibration.h"
#include "sweep/record.h"
#include "validate/solid_check.h"

namespace bsp::sweep {

namespace {

struct Operand {
  Scene scene;
  SolidBuild solid;
  double cpu_seconds = 0;
};

Scene operand_scene(const SolidOperand& o) {
  Scene scene = make_scene(o.scene, o.params);
  check_scene(scene, "scene " + scene.name);
  return scene;
}

Operand build_operand(Scene scene, Splitter& splitter, const Box& box) {
  require_closed_solid(scene.polygons, Tolerance::for_extent(box.diagonal()).plane_eps, scene.name);
  const double start = thread_cpu_seconds();
  SolidBuild solid = build_solid(scene.polygons, splitter, box);
  return {std::move(scene), std::move(solid), thread_cpu_seconds() - start};
}

void put_size(nlohmann::json& metrics, const std::string& prefix, const SolidSize& s) {
  metrics[prefix + "nodes"] = s.nodes;
  metrics[prefix + "in_leaves"] = s.in_leaves;
  metrics[prefix + "out_leaves"] = s.out_leaves;
  metrics[prefix + "depth"] = s.depth;
}

// Operand trees and merge cost, flat, so aggregation summarises every field.
nlohmann::json merge_metrics(const Operand& a, const Operand& b, const MergeStats& stats, const SolidCheck& check) {
  nlohmann::json m = nlohmann::json::object();
  for (const auto& [prefix, o] : {std::pair{"a_", &a}, std::pair{"b_", &b}}) {
    m[std::string(prefix) + "fragments"] = o->solid.fragments;
    put_size(m, prefix, solid_size(o->solid.solid));
  }
  m["partition_calls"] = stats.partition_calls;
  m["partition_nodes"] = stats.partition_nodes;
  m["shp_splits"] = stats.shp_splits;
  m["merge_nodes"] = stats.merge_nodes;
  m["cell_ops"] = stats.cell_ops;
  m["complement_nodes"] = stats.complement_nodes;
  m["inconsistent"] = stats.inconsistent;
  put_size(m, "before_", stats.before);
  put_size(m, "after_", stats.after);
  m["result_volume"] = check.tree_volume;
  m["boundary_faces"] = check.boundary.faces;
  return m;
}

// The boundary's closure: what must be zero, with what was done to close it. Volumes, not their
// relative errors: an error near 1e-16 is rounding noise that any change of summation order moves,
// while the volumes themselves compare within the gate's relative tolerance.
nlohmann::json boundary_invariants(const SolidCheck& c) {
  const bool volume_ok = c.boundary_volume_relative_error <= kVolumeRelativeTolerance;
  return {{"violations", c.boundary.edges.border_edges + (volume_ok ? 0 : 1)},
          {"border_edges", c.boundary.edges.border_edges},
          {"repeated_directed_edges", c.boundary.edges.repeated_directed},
          {"t_junctions_split", c.boundary.t_junctions},
          {"dropped_faces", c.boundary.dropped_faces},
          {"boundary_volume", c.boundary.volume}};
}

// Point membership and volume against CGAL: what must be zero, with what was counted apart.
nlohmann::json proof_validation(const SolidCheck& c) {
  const bool volume_ok = c.corefine_error.empty() && c.volume_relative_error <= kVolumeRelativeTolerance;
  return {{"violations", c.mismatches + (volume_ok ? 0 : 1)},
          {"points", c.points},
          {"compared", c.compared},
          {"mismatches", c.mismatches},
          {"on_operand_surface", c.on_operand},
          {"within_plane_eps", c.within_eps},
          {"within_plane_eps_disagree", c.within_eps_disagree},
          {"corefine_volume", c.exact_volume},
          {"corefine_error", c.corefine_error}};
}

}  // namespace

nlohmann::json run_merge_job(const Job& job, const std::optional<PlantedSlowdown>& plant) {
  const auto start = std::chrono::steady_clock::now();
  const auto specs = merge_operands(job);
  Scene scene_a = operand_scene(specs[0]), scene_b = operand_scene(specs[1]);
  const Box box = solid_box(bounds(scene_a), bounds(scene_b));
  const HeuristicVariant variant = parse_heuristic_variant(job.heuristic);
  auto splitter = make_splitter(variant.name, variant.params, job.seed);
  const Operand a = build_operand(std::move(scene_a), *splitter, box);
  const Operand b = build_operand(std::move(scene_b), *splitter, box);

  MergeStats stats;
  const SolidTree result = merge(a.solid.solid, b.solid.solid, *job.op, &stats);
  nlohmann::json timings = nlohmann::json::object();
  const bool planted = plant && plant->heuristic == job.heuristic;
  const TimedBatches batches = time_batches([&] { merge(a.solid.solid, b.solid.solid, *job.op); },
                                            planted ? plant->factor : 1.0);
  timings["merge_cpu_samples"] = batches.samples;
  timings["merge_cpu_merges"] = batches.runs;
  timings["merge_cpu_seconds"] = batches.median();
  timings["merge_seconds"] = stats.merge_seconds;
  timings["reduce_seconds"] = stats.reduce_seconds;
  timings["build_a_cpu_seconds"] = a.cpu_seconds;
  timings["build_b_cpu_seconds"] = b.cpu_seconds;

  const auto check_start = std::chrono::steady_clock::now();
  SolidCheckSettings settings;
  settings.points = job.points;
  settings.seed = job.seed;
  const SolidCheck check = check_set_operation(result, ExactSolid(a.scene.polygons), ExactSolid(b.scene.polygons),
                                               a.scene.polygons, b.scene.polygons, *job.op, settings);
  timings["check_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - check_start).count();
  timings["corefine_seconds"] = check.corefine_seconds;

  nlohmann::json id = job_identity(job);
  id["n_polygons"] = a.scene.polygons.size() + b.scene.polygons.size();
  for (std::size_t i = 0; i < 2; ++i) {
    const Scene& s = i == 0 ? a.scene : b.scene;
    id["operands"][i]["n_polygons"] = s.polygons.size();
    id["operands"][i]["scene_hash"] = scene_json(s)["hash"];
  }
  nlohmann::json record{{"key", job.key},
                        {"id", std::move(id)},
                        {"metrics", merge_metrics(a, b, stats, check)},
                        {"invariants", boundary_invariants(check)},
                        {"validation", proof_validation(check)},
                        {"ray_shooting", nullptr}};
  timings["job_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record["timings"] = std::move(timings);
  return record;
}

}  // namespace bsp::sweep
