#include "sweep/run_job.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "catalog.h"
#include "common/errors.h"
#include "geometry/segment2.h"
#include "metrics/statistics.h"
#include "metrics/tree_metrics.h"
#include "split/registry.h"
#include "sweep/calibration.h"
#include "sweep/record.h"
#include "sweep/run_doom_job.h"
#include "sweep/run_dynamic_jobs.h"
#include "sweep/run_merge_job.h"
#include "tree/build.h"
#include "validate/order_check.h"
#include "validate/ray_shoot_check.h"
#include "validate/tree_invariants.h"

namespace bsp::sweep {

namespace {

// The ray-shooting walk costs far more per ray than Embree (a 40 000-fragment saddle-grid tree has
// half a million validation rays): this many, spread over all of them, find a broken walk (it
// misses whole subtrees, so many rays) while keeping the quick suite within CI's budget.
constexpr std::size_t kMaxShootRays = 1500;

nlohmann::json invariants_json(const Tree& tree, const Scene& scene) {
  const InvariantReport r = check_tree_invariants(tree, scene.polygons);
  return {{"violations", r.violations}, {"first_problems", r.first_problems}};
}

ValidationSettings validation_settings(const Job& job) {
  ValidationSettings settings;
  settings.views = static_cast<int>(job.validation_views);
  return settings;
}

// null when the job asks for no views. A 2D tree is seen as walls from eyes in its plane.
nlohmann::json validation_json(const Tree& tree, const Job& job, bool flat, nlohmann::json& timings) {
  if (job.validation_views == 0) return nullptr;
  const ValidationSettings settings = validation_settings(job);
  nlohmann::json v = to_json(flat ? validate_segment_tree(tree, validation_eyes(tree.bounds, settings.views), settings)
                                  : validate_tree(tree, settings));
  split_timings(v, timings, "validation_");
  return v;
}

// The ray-shooting cross-check over at most kMaxShootRays of the validation's rays, evenly strided
// (deterministic); null when the job asks for no views.
nlohmann::json ray_shooting_json(const Tree& tree, const Job& job) {
  if (job.validation_views == 0) return nullptr;
  const ValidationSettings settings = validation_settings(job);
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  std::vector<Ray> all;
  for (const Vec3& eye : validation_eyes(tree.bounds, settings.views)) {
    const std::vector<Ray> more = validation_rays(fragments, tree.bounds, eye, settings);
    all.insert(all.end(), more.begin(), more.end());
  }
  const std::size_t stride = (all.size() + kMaxShootRays - 1) / kMaxShootRays;
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < all.size(); i += std::max<std::size_t>(stride, 1)) rays.push_back(all[i]);
  return to_json(check_ray_shooting(tree, EmbreeScene(fragments, tree.tol.plane_eps), rays));
}

Tree build_once(const Job& job, const Scene& scene) {
  BuildOptions options{.shape = job.shape};
  if (job.incremental) {
    options.order = InsertOrder::Shuffled;
    options.order_seed = insertion_order_seed(job.seed);
    return build_incremental_tree(scene.polygons, options);
  }
  const HeuristicVariant variant = parse_heuristic_variant(job.heuristic);
  auto splitter = make_splitter(variant.name, variant.params, job.seed);
  return build_tree(scene.polygons, *splitter, options);
}

// Spins until this thread has used `seconds` of CPU since `start` (the planted slowdown).
void burn_until(double start, double seconds) {
  volatile double sink = 0;
  while (thread_cpu_seconds() - start < seconds) sink = sink + 1;
}

// The build's timed batches (run_job.h).
void time_builds(const Job& job, const Scene& scene, double plant, nlohmann::json& timings) {
  const TimedBatches batches = time_batches([&] { build_once(job, scene); }, plant);
  timings["build_cpu_samples"] = batches.samples;
  timings["build_cpu_builds"] = batches.runs;
  timings["build_cpu_seconds"] = batches.median();
}

}  // namespace

double TimedBatches::median() const { return bsp::median(samples); }

TimedBatches time_batches(const std::function<void()>& work, double plant) {
  TimedBatches out;
  for (int s = 0; s < kBuildSamples; ++s) {
    const double start = thread_cpu_seconds();
    std::uint64_t batch = 0;
    do {
      work();
      ++batch;
    } while (thread_cpu_seconds() - start < kMinBatchSeconds);
    if (plant > 1) burn_until(start, plant * (thread_cpu_seconds() - start));
    out.samples.push_back((thread_cpu_seconds() - start) / static_cast<double>(batch));
    out.runs += batch;
  }
  return out;
}

PlantedSlowdown parse_planted_slowdown(const std::string& text) {
  const auto colon = text.rfind(':');
  PlantedSlowdown p;
  const char* end = text.data() + text.size();
  if (colon != std::string::npos && colon > 0) {
    p.heuristic = text.substr(0, colon);
    const auto [ptr, ec] = std::from_chars(text.data() + colon + 1, end, p.factor);
    if (ec == std::errc() && ptr == end && std::isfinite(p.factor) && p.factor >= 1) return p;
  }
  throw UsageError("BSPBENCH_PLANT_SLOWDOWN wants heuristic:factor with factor >= 1, not '" + text + "'");
}

nlohmann::json run_job(const Job& job, const std::optional<PlantedSlowdown>& plant) {
  if (job.op) return run_merge_job(job, plant);
  if (job.animate) return run_animate_job(job);
  if (job.occlude) return run_occlude_job(job, plant);
  if (job.doom) return run_doom_job(job, plant);
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = job_scene(job);
  nlohmann::json timings = nlohmann::json::object();
  const Tree tree = build_once(job, scene);
  const bool planted = plant && plant->heuristic == job.heuristic;
  time_builds(job, scene, planted ? plant->factor : 1.0, timings);

  MetricsSettings metric_settings;  // the defaults, with the job's seed for the metric rays
  metric_settings.seed = job.seed;
  // The query costs are defined for 3D scenes (cells, frustums and rays in space); a 2D tree gets
  // its size and shape.
  const bool flat = all_segments(scene.polygons);
  const double cpu = thread_cpu_seconds();
  nlohmann::json metrics = to_json(flat ? measure_tree(tree) : measure_tree(tree, metric_settings));
  timings["metrics_cpu_seconds"] = thread_cpu_seconds() - cpu;
  split_timings(metrics, timings, "");
  nlohmann::json id = job_identity(job);
  id["n_polygons"] = scene.polygons.size();
  const nlohmann::json described = scene_json(scene);
  id["scene_hash"] = described["hash"];
  id["scene_bounds"] = described["bounds"];
  if (described.contains("load")) id["scene_load"] = described["load"];
  nlohmann::json record{{"key", job.key},
                        {"id", std::move(id)},
                        {"metrics", std::move(metrics)},
                        {"invariants", invariants_json(tree, scene)},
                        {"validation", validation_json(tree, job, flat, timings)},
                        {"ray_shooting", flat ? nullptr : ray_shooting_json(tree, job)}};
  timings["job_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record["timings"] = std::move(timings);
  return record;
}

}  // namespace bsp::sweep
