#include "sweep/run_dynamic_jobs.h"

#include <chrono>
#include <nlohmann/json.hpp>

#include "animation.h"
#include "catalog.h"
#include "common/cpu_time.h"
#include "metrics/traversal_cost.h"
#include "split/registry.h"
#include "sweep/animation_run.h"
#include "sweep/calibration.h"
#include "sweep/occlusion_run.h"
#include "validate/tree_invariants.h"

namespace bsp::sweep {

namespace {

double mean(const std::vector<double>& xs) {
  double sum = 0;
  for (double x : xs) sum += x;
  return xs.empty() ? 0.0 : sum / static_cast<double>(xs.size());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

AnimationSpec animation_spec(const Job& job) {
  const AnimateParams& a = *job.animate;
  AnimationSpec s;
  s.scene = job.scene;
  s.scene_params = job.scene_params;
  s.moving = a.moving;
  s.frames = a.frames;
  s.object = a.object;
  s.object_n = a.object_n;
  s.size = a.size;
  s.speed = a.speed;
  s.spin = a.spin;
  s.seed = job.seed;
  return s;
}

// The summary's deterministic numbers, flat (nested objects prefixed), so aggregation summarises
// every field; its timings go to the record's timings.
nlohmann::json animate_metrics(const nlohmann::json& summary, double moving_fraction) {
  nlohmann::json m{{"moving_fraction", moving_fraction}};
  for (const char* k : {"frames", "frames_checked", "fragments_first", "fragments_last", "fragments_median",
                        "culled_nodes_visited_median"})
    m[k] = summary[k];
  if (summary.contains("update_work_total"))
    for (const auto& [k, v] : summary["update_work_total"].items()) m["work_" + k] = v;
  if (summary.contains("drift_last"))
    for (const auto& [k, v] : summary["drift_last"].items()) m["drift_" + k] = v;
  return m;
}

}  // namespace

nlohmann::json run_animate_job(const Job& job) {
  const auto start = std::chrono::steady_clock::now();
  const Animation animation(animation_spec(job));
  const HeuristicVariant variant = parse_heuristic_variant(job.heuristic);
  const HeuristicVariant object = parse_heuristic_variant(job_identity(job)["object_heuristic"].get<std::string>());
  auto updater = make_updater(job.animate->strategy, make_splitter(variant.name, variant.params, job.seed),
                              make_splitter(object.name, object.params, job.seed));
  AnimationRunSettings settings;
  settings.views.views = static_cast<int>(job.validation_views);
  settings.check_every = job.animate->check_every;
  settings.drift_every = job.animate->drift_every;
  const AnimationRun run = run_animation(
      animation, *updater, [&] { return make_splitter(variant.name, variant.params, job.seed); }, {}, settings);
  const nlohmann::json& s = run.summary;
  nlohmann::json id = job_identity(job);
  id["n_polygons"] = animation.static_scene().polygons.size() + animation.moving_polygons();
  id["static_polygons"] = animation.static_scene().polygons.size();
  id["moving_polygons"] = animation.moving_polygons();
  id["moving_fraction"] = animation.describe()["moving_fraction"];
  id["scene_hash"] = scene_json(animation.static_scene())["hash"];
  nlohmann::json timings{{"update_cpu_samples", run.update_seconds},
                         {"update_cpu_seconds", s.value("update_cpu_seconds_median", 0.0)},
                         {"update_cpu_seconds_max", s.value("update_cpu_seconds_max", 0.0)},
                         {"start_cpu_seconds", s["start_cpu_seconds"]}};
  nlohmann::json record{{"key", job.key},
                        {"id", std::move(id)},
                        {"metrics", animate_metrics(s, animation.describe()["moving_fraction"].get<double>())},
                        {"invariants", {{"violations", s["invariant_violations"]}, {"frames_checked", s["frames_checked"]}}},
                        {"validation",
                         {{"violations", s["order_violations"]},
                          {"frames_checked", s["frames_checked"]},
                          {"views", job.validation_views}}},
                        {"ray_shooting", nullptr}};
  timings["job_seconds"] = seconds_since(start);
  record["timings"] = std::move(timings);
  return record;
}

nlohmann::json run_occlude_job(const Job& job, const std::optional<PlantedSlowdown>& plant) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = make_scene(job.scene, job.scene_params);
  check_scene(scene, "scene " + scene.name);
  const HeuristicVariant variant = parse_heuristic_variant(job.heuristic);
  auto splitter = make_splitter(variant.name, variant.params, job.seed);
  const Tree tree = build_tree(scene.polygons, *splitter);
  const InvariantReport invariants = check_tree_invariants(tree, scene.polygons);
  const double setup_start = thread_cpu_seconds();
  const Occluder occluder(tree);
  const double setup_seconds = thread_cpu_seconds() - setup_start;
  const std::vector<Frustum> views = metric_views(tree.bounds, job.validation_views);
  nlohmann::json metrics = nlohmann::json::object(), validation{{"violations", 0}, {"missed_fragments", 0}, {"rays", 0}};
  std::vector<double> per_seen, per_frustum;
  bool ok = true;
  for (const Frustum& v : views) {
    const nlohmann::json r = occlusion_view(tree, occluder, v, {}, ok);
    for (const auto& [k, x] : r.items())
      if (x.is_number_unsigned()) metrics[k] = metrics.value(k, std::uint64_t{0}) + x.get<std::uint64_t>();
    metrics["views_covered"] = metrics.value("views_covered", 0) + (r["covered"].get<bool>() ? 1 : 0);
    per_seen.push_back(r["emitted_per_seen"].get<double>());
    per_frustum.push_back(r["emitted_per_frustum_culled"].get<double>());
    validation["violations"] = validation["violations"].get<std::uint64_t>() + r["missed_rays"].get<std::uint64_t>();
    validation["missed_fragments"] =
        validation["missed_fragments"].get<std::uint64_t>() + r["missed_fragments"].get<std::uint64_t>();
    validation["rays"] = validation["rays"].get<std::uint64_t>() + r["rays"].get<std::uint64_t>();
  }
  for (const char* k : {"missed_fragments", "missed_rays", "rays", "rays_hitting"}) metrics.erase(k);
  metrics["fragments"] = tree.fragments.size();
  metrics["emitted_per_seen_mean"] = mean(per_seen);
  metrics["emitted_per_frustum_culled_mean"] = mean(per_frustum);
  const bool planted = plant && plant->heuristic == job.heuristic;
  const TimedBatches batches = time_batches(
      [&] {
        for (const Frustum& v : views) occluder.visible(v);
      },
      planted ? plant->factor : 1.0);
  const double views_count = std::max<double>(1, static_cast<double>(views.size()));
  nlohmann::json timings{{"occlude_cpu_samples", batches.samples},
                         {"occlude_cpu_seconds", batches.median() / views_count},
                         {"occlude_cpu_runs", batches.runs},
                         {"occluder_setup_cpu_seconds", setup_seconds}};
  nlohmann::json id = job_identity(job);
  id["n_polygons"] = scene.polygons.size();
  id["scene_hash"] = scene_json(scene)["hash"];
  nlohmann::json record{{"key", job.key},
                        {"id", std::move(id)},
                        {"metrics", std::move(metrics)},
                        {"invariants", {{"violations", invariants.violations}}},
                        {"validation", std::move(validation)},
                        {"ray_shooting", nullptr}};
  timings["job_seconds"] = seconds_since(start);
  record["timings"] = std::move(timings);
  return record;
}

}  // namespace bsp::sweep
