// bspbench compare: every heuristic (or a list) on the same scene over K seeds. Seed k of a run is
// --seed + k for both the scene and the heuristic. Each metric is reported as its mean with a 95%
// Student-t interval over the seeds (metrics/statistics.h), with two Embree checks of every tree
// summed over the seeds: its back-to-front orders (validate/order_check.h) and its ray shooting
// (validate/ray_shoot_check.h). --views sets both the metrics' views and the validation's eyes.
// With --kernel exact each tree is built in the exact kernel, measured on its view (vertices from
// planes) and its orders checked exactly (validate/exact_order_check.h); the ray-shooting check,
// a float traversal, is not run then (its counts are 0). Exit code 1 when any check fails.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "catalog.h"
#include "mesh_scenes.h"
#include "cli/commands.h"
#include "cli/metrics_args.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "common/progress.h"
#include "experiments/draw/draw.h"
#include "io/mesh_reader.h"
#include "metrics/statistics.h"
#include "metrics/tree_metrics.h"
#include "experiments/heuristic_choice.h"
#include "split/registry.h"
#include "tree/build.h"
#include "validate/exact_order_check.h"
#include "validate/order_check.h"
#include "validate/ray_shoot_check.h"

namespace bsp::cli {

namespace {

// Upper bound of --seeds: each seed builds, measures and validates every heuristic once.
constexpr long long kMaxSeeds = 1000;
// The columns of the text table.
constexpr const char* kTableMetrics[] = {"fragments", "max_depth", "e_point", "e_line", "ray_nodes_visited",
                                         "culled_nodes_visited"};

struct CompareSpec {
  std::string scene;                 // a generator, or mesh:NAME
  std::optional<std::string> input;  // a mesh file instead of `scene`
  ParamAssignments scene_params;  // without the seed
  std::uint64_t seed = 1;
  std::uint64_t seeds = 1;
  std::vector<std::string> heuristics;
  BuildOptions options;
  Kernel kernel = Kernel::Float;
  MetricsSettings metrics;
  ValidationSettings validation;
};

std::vector<std::string> heuristic_list(const std::string& text) {
  std::vector<std::string> out;
  if (text == "all") {
    for (const auto& h : heuristics()) out.push_back(h.name);
    return out;
  }
  std::stringstream in(text);
  for (std::string name; std::getline(in, name, ',');) {
    experiments::params_of(name);  // rejects an unknown name now
    out.push_back(name);
  }
  if (out.empty()) throw UsageError("--heuristics wants all or a comma-separated list of names");
  return out;
}

CompareSpec parse(Args& args) {
  CompareSpec s;
  s.input = args.option("--input");
  const auto scene = args.option("--scene");
  if (s.input.has_value() == scene.has_value()) throw UsageError("give either --scene NAME or --input FILE");
  s.scene = scene.value_or(*s.input);
  if (const auto n = args.option("--n")) s.scene_params.emplace_back("n", *n);
  for (const auto& kv : args.options("--scene-param")) s.scene_params.push_back(parse_assignment(kv));
  if (s.input && !s.scene_params.empty()) throw UsageError("--n and --scene-param apply to --scene, not --input");
  for (const auto& [k, v] : s.scene_params)
    if (k == "seed") throw UsageError("give the scene's seed with --seed");
  s.seed = static_cast<std::uint64_t>(args.integer("--seed", 0, 9'000'000'000'000'000LL).value_or(1));
  s.seeds = static_cast<std::uint64_t>(args.integer("--seeds", 1, kMaxSeeds).value_or(1));
  s.options = build_options_from(args, s.seed);
  const auto heuristics = args.option("--heuristics");
  // An incremental build consults no heuristic: one tree per seed, labelled "incremental".
  if (s.options.incremental && heuristics)
    throw UsageError("--incremental consults no heuristic (the insertion order picks the planes); drop --heuristics");
  if (!s.options.incremental && !heuristics) throw UsageError("missing option --heuristics");
  s.heuristics = s.options.incremental ? std::vector<std::string>{std::string(kIncrementalLabel)}
                                       : heuristic_list(*heuristics);
  s.metrics = metrics_settings_from(args, s.seed);
  s.validation.views = static_cast<int>(s.metrics.views);
  return s;
}

// --kernel, checked against the build options and the scene as the other commands do.
Kernel kernel_for(Args& args, const CompareSpec& s, const Scene& scene) {
  return kernel_from(args, TreeArgs{"", {}, s.options, s.seed}, scene);
}

// A generated scene is made anew for each seed; a mesh (a file or mesh:NAME) has no seed, so it is
// read once and every seed only feeds the heuristic.
bool seeded_scene(const CompareSpec& s) { return !s.input && !is_mesh_scene(s.scene); }

Scene scene_for(const CompareSpec& s, std::uint64_t seed) {
  if (s.input) {
    Scene scene = read_mesh(*s.input);
    check_scene(scene, *s.input);
    return scene;
  }
  ParamAssignments given = s.scene_params;
  if (seeded_scene(s)) given.emplace_back("seed", std::to_string(seed));
  Scene scene = make_scene(s.scene, given);
  check_scene(scene, "scene " + scene.name);
  return scene;
}

// One build of `heuristic` at `seed`: its metrics and its checks.
struct Run {
  nlohmann::json metrics;
  ValidationReport order;
  RayShootCheck ray_shoot;
};

Run run_once(const CompareSpec& s, const Scene& scene, const std::string& heuristic, std::uint64_t seed) {
  TreeArgs t{heuristic, {}, s.options, seed};
  t.options.order_seed = insertion_order_seed(seed);
  MetricsSettings m = s.metrics;
  m.seed = seed;
  if (s.kernel == Kernel::Exact) {
    const ExactTree exact = build_exact_from_args(scene, t);
    return {to_json(experiments::measure_drawing(exact.tree, scene.polygons, m)),
            validate_exact_tree(exact, s.validation).report, RayShootCheck{}};
  }
  const Tree tree = build_from_args(scene, t);
  return {to_json(experiments::measure_drawing(tree, scene.polygons, m)), validate_tree(tree, s.validation),
          check_ray_shooting(tree, s.validation)};
}

// The checks summed over the runs; `failures` counts order violations and ray-shooting mismatches.
nlohmann::json validation_totals(const std::vector<Run>& runs) {
  std::uint64_t violations = 0, order_rays = 0, mismatches = 0, shoot_ties = 0, shoot_rays = 0;
  for (const Run& r : runs) {
    violations += r.order.violations;
    order_rays += r.order.rays;
    mismatches += r.ray_shoot.mismatches;
    shoot_ties += r.ray_shoot.ties();
    shoot_rays += r.ray_shoot.rays;
  }
  return {{"failures", violations + mismatches},
          {"order_violations", violations},
          {"order_rays", order_rays},
          {"ray_shoot_mismatches", mismatches},
          {"ray_shoot_ties", shoot_ties},
          {"ray_shoot_rays", shoot_rays}};
}

// Mean and interval of every numeric metric over the runs, the checks summed, and each run.
nlohmann::json summarize_runs(const std::string& heuristic, const std::vector<Run>& runs) {
  std::map<std::string, std::vector<double>> samples;
  nlohmann::json per_seed = nlohmann::json::array();
  for (const Run& r : runs) {
    for (const auto& [k, v] : r.metrics.items())
      if (v.is_number()) samples[k].push_back(v.get<double>());
    per_seed.push_back({{"metrics", r.metrics}, {"order_check", to_json(r.order)}, {"ray_shoot_check", to_json(r.ray_shoot)}});
  }
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& [k, xs] : samples) metrics[k] = to_json(summarize(xs));
  return {{"heuristic", heuristic},
          {"metrics", std::move(metrics)},
          {"validation", validation_totals(runs)},
          {"runs", std::move(per_seed)}};
}

// Each seed of a generated scene makes its own scene: its seed, content hash and bounding box. A
// mesh is one scene, with no seed.
nlohmann::json scene_instances(const CompareSpec& s, const std::vector<Scene>& scenes) {
  nlohmann::json out = nlohmann::json::array();
  for (std::uint64_t k = 0; k < scenes.size(); ++k) {
    const nlohmann::json j = scene_json(scenes[k]);
    const nlohmann::json seed = seeded_scene(s) ? nlohmann::json(s.seed + k) : nlohmann::json(nullptr);
    out.push_back({{"seed", seed}, {"scene_hash", j["hash"]}, {"scene_bounds", j["bounds"]}});
  }
  return out;
}

nlohmann::json header(const CompareSpec& s, const std::vector<Scene>& scenes) {
  nlohmann::json seeds = nlohmann::json::array();
  for (std::uint64_t k = 0; k < s.seeds; ++k) seeds.push_back(s.seed + k);
  nlohmann::json params = scene_json(scenes.front())["params"];
  params.erase("seed");
  nlohmann::json out = {{"scene", s.scene},
          {"scene_params", params},
          {"seeds", seeds},
          {"scenes", scene_instances(s, scenes)},
          {"shape", shape_name(s.options.shape)},
          {"build", s.options.incremental ? "incremental" : "recursive"},
          {"order", s.options.order == InsertOrder::Shuffled ? "shuffled" : "given"},
          {"cell_margin", s.metrics.cell_margin},
          {"views", s.metrics.views},
          {"rays", s.metrics.rays}};
  if (s.kernel != Kernel::Float) out["kernel"] = kernel_name(s.kernel);
  return out;
}

std::string mean_and_interval(const nlohmann::json& summary) {
  char buf[64];
  const double mean = summary["mean"].get<double>();
  if (summary["ci95"].is_null()) {
    std::snprintf(buf, sizeof buf, "%.4g", mean);
  } else {
    const double half = (summary["ci95"][1].get<double>() - summary["ci95"][0].get<double>()) / 2;
    std::snprintf(buf, sizeof buf, "%.4g ± %.2g", mean, half);
  }
  return buf;
}

void print_table(const nlohmann::json& out) {
  std::cout << "scene " << out["scene"].get<std::string>() << " " << out["scene_params"].dump() << ", seeds "
            << out["seeds"].dump() << ", " << out["shape"].get<std::string>() << " "
            << out["build"].get<std::string>() << "\n";
  std::cout << "heuristic";
  for (const char* m : kTableMetrics) std::cout << "\t" << m;
  std::cout << "\tcheck failures\n";
  for (const auto& h : out["heuristics"]) {
    std::cout << h["heuristic"].get<std::string>();
    for (const char* m : kTableMetrics) std::cout << "\t" << mean_and_interval(h.at("metrics").at(m));
    std::cout << "\t" << h["validation"]["failures"].get<std::uint64_t>() << "\n";
  }
}

int run(Args& args) {
  const bool json = args.flag("--json");
  CompareSpec spec = parse(args);
  std::vector<Scene> scenes;
  for (std::uint64_t k = 0; k < (seeded_scene(spec) ? spec.seeds : 1); ++k) scenes.push_back(scene_for(spec, spec.seed + k));
  spec.kernel = kernel_for(args, spec, scenes.front());
  args.finish();
  nlohmann::json out = header(spec, scenes);
  out["heuristics"] = nlohmann::json::array();
  std::uint64_t failures = 0;
  // Progress on stderr, a run of each heuristic and seed weighing alike.
  const std::uint64_t total = spec.heuristics.size() * spec.seeds;
  Progress progress(std::clog, ::isatty(STDERR_FILENO) != 0, "compare", "runs", total, static_cast<double>(total));
  for (const auto& h : spec.heuristics) {
    std::vector<Run> runs;
    for (std::uint64_t k = 0; k < spec.seeds; ++k) {
      runs.push_back(run_once(spec, scenes[seeded_scene(spec) ? k : 0], h, spec.seed + k));
      progress.job_done(1.0);
    }
    out["heuristics"].push_back(summarize_runs(h, runs));
    failures += out["heuristics"].back()["validation"]["failures"].get<std::uint64_t>();
  }
  progress.finish();
  out["validation_failures"] = failures;
  if (json)
    std::cout << out.dump() << "\n";
  else
    print_table(out);
  return failures ? 1 : 0;
}

}  // namespace

Command compare_command() {
  static const std::string usage =
      "(--scene NAME [--n N] [--scene-param k=v]... | --input FILE) [--seed S] (--heuristics all|NAME[,NAME]... | "
      "--incremental "
      "[--order given|shuffled]) [--seeds K] [--shape strict|coarse|leafy] " + std::string(kKernelUsage) + " " +
      std::string(kMetricsUsage) + " [--json]";
  static const OptionHelps own = {
      {"--scene NAME", kSceneOptions[0].meaning},
      {"--n N", kSceneOptions[1].meaning},
      {"--scene-param k=v", kSceneOptions[3].meaning},
      {"--input FILE", "a mesh file (OBJ, OFF, PLY, STL) instead of --scene; like mesh:NAME it is read once and the "
                       "seeds feed only the heuristics"},
      {"--seed S", "seed of the first run; run k uses S + k for a generated scene and the heuristic (default 1)"},
      {"--heuristics all|NAME[,NAME]...", "every registered heuristic, or a comma-separated list"},
      {"--seeds K", "runs per heuristic, each with its own seed (default 1)"}};
  return {"compare", usage,
          "every heuristic on one scene over K seeds: each metric's mean and 95% interval, and validation", run,
          concat({own, kBuildModeOptions, {kKernelOption}, kMetricsOptions, kJsonOption})};
}

}  // namespace bsp::cli
