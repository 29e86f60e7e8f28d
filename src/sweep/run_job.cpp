#include "sweep/run_job.h"

#include <chrono>
#include <nlohmann/json.hpp>

#include "catalog.h"
#include "metrics/tree_metrics.h"
#include "split/registry.h"
#include "sweep/calibration.h"
#include "sweep/record.h"
#include "tree/build.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

namespace bsp::sweep {

namespace {

nlohmann::json invariants_json(const Tree& tree, const Scene& scene) {
  const InvariantReport r = check_tree_invariants(tree, scene.polygons);
  return {{"violations", r.violations}, {"first_problems", r.first_problems}};
}

// null when the job asks for no views.
nlohmann::json validation_json(const Tree& tree, const Job& job, nlohmann::json& timings) {
  if (job.validation_views == 0) return nullptr;
  ValidationSettings settings;
  settings.views = static_cast<int>(job.validation_views);
  nlohmann::json v = to_json(validate_tree(tree, settings));
  split_timings(v, timings, "validation_");
  return v;
}

}  // namespace

nlohmann::json run_job(const Job& job) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = make_scene(job.scene, job.scene_params);
  check_scene(scene, "scene " + scene.name);
  auto splitter = make_splitter(job.heuristic, {}, job.seed);
  nlohmann::json timings = nlohmann::json::object();
  double cpu = thread_cpu_seconds();
  const Tree tree = build_tree(scene.polygons, *splitter, {.shape = job.shape});
  timings["build_cpu_seconds"] = thread_cpu_seconds() - cpu;

  MetricsSettings metric_settings;  // the defaults, with the job's seed for the metric rays
  metric_settings.seed = job.seed;
  cpu = thread_cpu_seconds();
  nlohmann::json metrics = to_json(measure_tree(tree, metric_settings));
  timings["metrics_cpu_seconds"] = thread_cpu_seconds() - cpu;
  split_timings(metrics, timings, "");
  nlohmann::json id = job_identity(job);
  id["n_polygons"] = scene.polygons.size();
  const nlohmann::json described = scene_json(scene);
  id["scene_hash"] = described["hash"];
  id["scene_bounds"] = described["bounds"];
  nlohmann::json record{{"key", job.key},
                        {"id", std::move(id)},
                        {"metrics", std::move(metrics)},
                        {"invariants", invariants_json(tree, scene)},
                        {"validation", validation_json(tree, job, timings)}};
  timings["job_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record["timings"] = std::move(timings);
  return record;
}

}  // namespace bsp::sweep
