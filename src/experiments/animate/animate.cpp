#include "experiments/animate/animate.h"

#include <numbers>

#include <nlohmann/json.hpp>

#include "animation.h"
#include "catalog.h"
#include "common/hash.h"
#include "dynamic/updater.h"
#include "experiments/animate/animation_run.h"
#include "experiments/reference_build.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr TimingField kTimings[] = {
    {"update_cpu_samples", TimingRole::GatedSamples, "thread CPU seconds of each frame's update, frames 1 on"},
    {"update_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the first frame, one batch before each update: the gate divides each sample by it (experiments/reference_build.h)"},
    {"update_cpu_seconds", TimingRole::SamplesMedian, "the median of update_cpu_samples"},
    {"update_cpu_seconds_max", TimingRole::Cpu, "the slowest update"},
    {"start_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the strategy's first frame (its whole build)"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

// What aggregation groups by and fits growth of (experiments/kind.h).
constexpr std::string_view kGroupBy[] = {"strategy", "object_heuristic", "moving", "speed", "frames", "object", "object_n", "size", "spin"};
constexpr std::string_view kGrowthMetrics[] = {"fragments_last", "work_nodes_built"};
constexpr std::string_view kGrowthTimings[] = {"update_cpu_seconds"};

// The summary's deterministic numbers, flat (nested objects prefixed), so aggregation summarises
// every field; its timings go to the record's timings.
json animate_metrics(const json& summary, double moving_fraction) {
  json m{{"moving_fraction", moving_fraction}};
  for (const char* k : {"frames", "frames_checked", "fragments_first", "fragments_last", "fragments_median",
                        "culled_nodes_visited_median"})
    m[k] = summary[k];
  if (summary.contains("update_work_total"))
    for (const auto& [k, v] : summary["update_work_total"].items()) m["work_" + k] = v;
  if (summary.contains("drift_last"))
    for (const auto& [k, v] : summary["drift_last"].items()) m["drift_" + k] = v;
  return m;
}

std::string real(double x) { return json(x).dump(); }

// The same bounds as `bspbench animate` (generators/animation.h checks them again when a job runs).
std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"scenes", "sizes", "heuristics", "strategies", "moving", "speeds", "seeds", "frames", "object",
                         "object_n", "size", "spin", "check_every", "drift_every", "views"});
  auto b = std::make_unique<AnimateBlock>();
  std::vector<const GeneratorInfo*> sized;
  b->scenes = r.generator_names(r.required(j, path, "scenes"), child(path, "scenes"), "animation", sized);
  b->sizes = r.generator_sizes(j, path, sized);
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  if (const json* s = r.optional(j, "strategies"))
    b->strategies = r.names(*s, child(path, "strategies"), "leave \"strategies\" out for every strategy",
                            [](const std::string& name) {
                              const auto known = updater_names();
                              if (std::find(known.begin(), known.end(), name) == known.end())
                                throw UsageError("unknown update strategy '" + name + "' (known: " + join(known) + ")");
                            });
  std::map<std::string, std::string> seen;
  r.each(r.required(j, path, "moving"), child(path, "moving"), "give at least one count", [&](const json& v, const std::string& p) {
    b->moving.push_back(static_cast<std::uint32_t>(r.integer(v, p, 0, 1000)));
    r.once(seen, std::to_string(b->moving.back()), p);
  });
  seen.clear();
  r.each(r.required(j, path, "speeds"), child(path, "speeds"), "give at least one speed", [&](const json& v, const std::string& p) {
    b->speeds.push_back(r.real(v, p, 0, 1));
    r.once(seen, real(b->speeds.back()), p);
  });
  b->seeds = r.seeds(j, path);
  if (const json* v = r.optional(j, "frames")) b->frames = static_cast<std::uint32_t>(r.integer(*v, child(path, "frames"), 1, 100000));
  if (const json* v = r.optional(j, "object")) {
    b->object = r.string(*v, child(path, "object"));
    if (b->object != kSceneGroups && !r.at(child(path, "object"), [&] { return find_generator(b->object).closed_solid; }))
      r.fail(child(path, "object"),
             "'" + b->object + "' is not a closed solid (bspbench scenes) or '" + std::string(kSceneGroups) + "'");
  }
  if (const json* v = r.optional(j, "object_n")) b->object_n = r.integer(*v, child(path, "object_n"), 1, 100000);
  if (const json* v = r.optional(j, "size")) b->size = r.real(*v, child(path, "size"), 0, 0.5, true);
  if (const json* v = r.optional(j, "spin")) b->spin = r.real(*v, child(path, "spin"), 0, std::numbers::pi);
  if (const json* v = r.optional(j, "check_every"))
    b->check_every = static_cast<std::uint32_t>(r.integer(*v, child(path, "check_every"), 1, 100000));
  if (const json* v = r.optional(j, "drift_every"))
    b->drift_every = static_cast<std::uint32_t>(r.integer(*v, child(path, "drift_every"), 0, 100000));
  if (const json* v = r.optional(j, "views")) b->views = static_cast<std::uint32_t>(r.integer(*v, child(path, "views"), 0, kMaxViews));
  return b;
}

// What reports must hold of an animate run's identity: its strategy, moving count and speed.
bool strategy_moving_and_speed(const json& id) {
  return id.contains("strategy") && id["strategy"].is_string() && id.contains("moving") &&
         id["moving"].is_number_unsigned() && id.contains("speed") && id["speed"].is_number();
}

AnimationSpec animation_spec(const SceneRun& s, const AnimateParams& a) {
  AnimationSpec spec;
  spec.scene = s.scene;
  spec.scene_params = s.scene_params;
  spec.moving = a.moving;
  spec.frames = a.frames;
  spec.object = a.object;
  spec.object_n = a.object_n;
  spec.size = a.size;
  spec.speed = a.speed;
  spec.spin = a.spin;
  spec.seed = s.seed;
  return spec;
}

}  // namespace

Jobs AnimateBlock::expand() const {
  const std::vector<std::string> all_strategies = strategies.empty() ? updater_names() : strategies;
  Jobs out;
  for (const auto& name : scenes) {
    const GeneratorInfo& g = find_generator(name);
    for (auto n : sizes_in_range(g, sizes))
      for (const auto& h : per_node_choices_or_all(heuristics, "an animation block")) {
        for (const auto& strategy : all_strategies)
          for (auto count : moving)
            for (auto speed : speeds)
              for (auto seed : seeds)
                out.push_back(std::make_shared<AnimateJob>(
                    SceneRun::generated(g, {}, h, Shape::Strict, seed, n, views),
                    AnimateParams{strategy, count, frames, object, object_n, size, speed, spin, check_every, drift_every}));
      }
  }
  return out;
}

// The key adds the animation and strategy to the drawing run's.
AnimateJob::AnimateJob(SceneRun scene, AnimateParams animate) : scene_(std::move(scene)), animate_(std::move(animate)) {
  Hasher h;
  h.add_string("animate");
  h.add_string(scene_.hash(scene_.key_scene_text()));
  const AnimateParams& a = animate_;
  h.add_string(a.strategy);
  h.add_string(object_heuristic());
  h.add_string(a.object);
  for (const std::uint64_t v : {std::uint64_t{a.moving}, std::uint64_t{a.frames}, a.object_n,
                                std::uint64_t{a.check_every}, std::uint64_t{a.drift_every}})
    h.add_u64(v);
  for (const double v : {a.size, a.speed, a.spin}) h.add_string(real(v));
  set_identity(h.hex(), scene_.n);
}

std::string AnimateJob::object_heuristic() const {
  return animate_.strategy == "torres" ? "halving" : scene_.heuristic->label;
}

nlohmann::json AnimateJob::identity() const {
  const AnimateParams& a = animate_;
  json id = scene_.identity("animate");
  id["strategy"] = a.strategy;
  id["object_heuristic"] = object_heuristic();
  id["moving"] = a.moving;
  id["frames"] = a.frames;
  id["object"] = a.object;
  id["object_n"] = a.object_n;
  id["size"] = a.size;
  id["speed"] = a.speed;
  id["spin"] = a.spin;
  id["check_every"] = a.check_every;
  id["drift_every"] = a.drift_every;
  std::string command = "bspbench animate --scene " + scene_.scene;
  if (scene_.n > 0) command += " --n " + std::to_string(scene_.n);
  command += " --seed " + std::to_string(scene_.seed) + " --moving " + std::to_string(a.moving) + " --frames " +
             std::to_string(a.frames) + " --object " + a.object + " --object-n " + std::to_string(a.object_n) +
             " --size " + real(a.size) + " --speed " + real(a.speed) + " --spin " + real(a.spin) + " --strategy " +
             a.strategy + scene_.heuristic->arguments();
  if (object_heuristic() != scene_.heuristic->label) command += " --object-heuristic " + object_heuristic();
  id["command"] = command + " --views " + std::to_string(scene_.views) + " --check-every " +
                  std::to_string(a.check_every) + " --drift-every " + std::to_string(a.drift_every);
  return id;
}

nlohmann::json AnimateJob::run(const RunContext&) const {
  const double start = wall_seconds();
  const Animation animation(animation_spec(scene_, animate_));
  const HeuristicChoice& h = *scene_.heuristic;
  const HeuristicChoice object = HeuristicChoice::parse(object_heuristic());
  auto updater = make_updater(animate_.strategy, h.splitter(scene_.seed), object.splitter(scene_.seed));
  AnimationRunSettings settings;
  settings.views.views = static_cast<int>(scene_.views);
  settings.check_every = animate_.check_every;
  settings.drift_every = animate_.drift_every;
  const ReferenceBuild reference(animation.frame(0).polygons);
  settings.reference = [&] { reference.run(); };
  const AnimationRun run =
      run_animation(animation, *updater, [&] { return h.splitter(scene_.seed); }, {}, settings);
  const json& s = run.summary;
  const double moving_fraction = animation.describe()["moving_fraction"].get<double>();
  json id = identity();
  id["n_polygons"] = animation.static_scene().polygons.size() + animation.moving_polygons();
  id["static_polygons"] = animation.static_scene().polygons.size();
  id["moving_polygons"] = animation.moving_polygons();
  id["moving_fraction"] = animation.describe()["moving_fraction"];
  id["scene_hash"] = scene_json(animation.static_scene())["hash"];
  json timings{{"update_cpu_samples", run.update_seconds},
               {"update_reference_samples", run.reference_seconds},
               {"update_cpu_seconds", s.value("update_cpu_seconds_median", 0.0)},
               {"update_cpu_seconds_max", s.value("update_cpu_seconds_max", 0.0)},
               {"start_cpu_seconds", s["start_cpu_seconds"]}};
  json invariants{{"violations", s["invariant_violations"]}, {"frames_checked", s["frames_checked"]}};
  json validation{{"violations", s["order_violations"]}, {"frames_checked", s["frames_checked"]}, {"views", scene_.views}};
  return make_record(*this, std::move(id), animate_metrics(s, moving_fraction), std::move(invariants),
                     std::move(validation), nullptr, std::move(timings), start);
}

const Kind& animate_kind() {
  static const Kind kind{
      .name = "animate",
      .suite_key = "animations",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .timing_group_field = "strategy",
      .identity_ok = strategy_moving_and_speed,
      .schema_section = "ANIMATE RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
