#include "experiments/occlude/occlude.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/cpu_time.h"
#include "common/hash.h"
#include "experiments/occlude/occlusion_run.h"
#include "experiments/reference_build.h"
#include "metrics/traversal_cost.h"
#include "tree/build.h"
#include "validate/tree_invariants.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr std::uint32_t kDefaultViews = 4;

constexpr TimingField kTimings[] = {
    {"occlude_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per culling of every view, one per timed batch of at least 2 ms"},
    {"occlude_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the same input, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"occlude_cpu_seconds", TimingRole::SamplesMedian, "the median of occlude_cpu_samples, divided by the views"},
    {"occlude_cpu_runs", TimingRole::SampleCount, "cullings of every view timed: depends on the machine's speed"},
    {"occluder_setup_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the subtree boxes (once per tree)"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

// What aggregation fits growth of (experiments/kind.h).
constexpr std::string_view kGrowthMetrics[] = {"emitted", "seen_by_embree", "beam_nodes"};
constexpr std::string_view kGrowthTimings[] = {"occlude_cpu_seconds"};

double mean(const std::vector<double>& xs) {
  double sum = 0;
  for (double x : xs) sum += x;
  return xs.empty() ? 0.0 : sum / static_cast<double>(xs.size());
}

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"scenes", "sizes", "heuristics", "seeds", "views"});
  auto b = std::make_unique<OccludeBlock>();
  std::vector<const GeneratorInfo*> sized;
  b->scenes = r.generator_names(r.required(j, path, "scenes"), child(path, "scenes"), "occlusion culling", sized);
  b->sizes = r.generator_sizes(j, path, sized);
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  b->seeds = r.seeds(j, path);
  b->views = kDefaultViews;
  if (const json* v = r.optional(j, "views")) b->views = static_cast<std::uint32_t>(r.integer(*v, child(path, "views"), 1, kMaxViews));
  return b;
}

// Every view's culling, summed; the rays' proof into `validation`.
json cull_views(const Tree& tree, const Occluder& occluder, const std::vector<Frustum>& views, json& validation) {
  json metrics = json::object();
  std::vector<double> per_seen, per_frustum;
  bool ok = true;
  for (const Frustum& v : views) {
    const json r = occlusion_view(tree, occluder, v, {}, ok);
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
  return metrics;
}

}  // namespace

Jobs OccludeBlock::expand() const {
  Jobs out;
  for (const auto& name : scenes) {
    const GeneratorInfo& g = find_generator(name);
    for (auto n : sizes_in_range(g, sizes))
      for (const auto& h : choices_or_all(heuristics)) {
        for (auto seed : seeds)
          out.push_back(std::make_shared<OccludeJob>(SceneRun::generated(g, {}, h, Shape::Strict, seed, n, views)));
      }
  }
  return out;
}

// The key adds the kind to the drawing run's.
OccludeJob::OccludeJob(SceneRun scene) : scene_(std::move(scene)) {
  Hasher h;
  h.add_string("occlude");
  h.add_string(scene_.hash(scene_.key_scene_text()));
  set_identity(h.hex(), scene_.n);
}

nlohmann::json OccludeJob::identity() const {
  json id = scene_.identity("occlude");
  std::string command = "bspbench occlude --scene " + scene_.scene;
  if (scene_.n > 0) command += " --n " + std::to_string(scene_.n);
  id["command"] = command + " --seed " + std::to_string(scene_.seed) + scene_.heuristic->arguments() + " --views " +
                  std::to_string(scene_.views);
  return id;
}

nlohmann::json OccludeJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const Scene scene = scene_.make_scene();
  const Tree tree = scene_.heuristic->build(scene.polygons, {}, scene_.seed);
  const InvariantReport invariants = check_tree_invariants(tree, scene.polygons);
  const double setup_start = thread_cpu_seconds();
  const Occluder occluder(tree);
  const double setup_seconds = thread_cpu_seconds() - setup_start;
  const std::vector<Frustum> views = metric_views(tree.bounds, scene_.views);
  json validation{{"violations", 0}, {"missed_fragments", 0}, {"rays", 0}};
  json metrics = cull_views(tree, occluder, views, validation);
  const ReferenceBuild reference(scene.polygons);
  const TimedBatches batches = time_batches(
      [&] {
        for (const Frustum& v : views) occluder.visible(v);
      },
      context.slowdown(scene_.heuristic->label), [&] { reference.run(); });
  const double views_count = std::max<double>(1, static_cast<double>(views.size()));
  json timings{{"occlude_cpu_samples", batches.samples},
               {"occlude_reference_samples", batches.reference},
               {"occlude_cpu_seconds", batches.median() / views_count},
               {"occlude_cpu_runs", batches.runs},
               {"occluder_setup_cpu_seconds", setup_seconds}};
  json id = identity();
  id["n_polygons"] = scene.polygons.size();
  id["scene_hash"] = scene_json(scene)["hash"];
  return make_record(*this, std::move(id), std::move(metrics), {{"violations", invariants.violations}},
                     std::move(validation), nullptr, std::move(timings), start);
}

const Kind& occlude_kind() {
  static const Kind kind{
      .name = "occlude",
      .suite_key = "occlusions",
      .parse = parse_block,
      .timings = kTimings,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .timing_group_word = "occlude",
      .schema_section = "OCCLUDE RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
