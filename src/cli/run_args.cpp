#include "cli/run_args.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/errors.h"
#include "experiments/draw/draw.h"
#include "io/mesh_reader.h"
#include "geometry/segment2.h"
#include "mesh_scenes.h"
#include "experiments/heuristic_choice.h"

namespace bsp::cli {

namespace {

// What loading a mesh file changed, as one warning line on stderr (nothing when it changed nothing).
void warn_about_load(const Scene& scene) {
  const SceneLoadStats& s = scene.load;
  if (s.triangulated + s.dropped_degenerate + s.dropped_duplicate_vertex == 0) return;
  std::cerr << "bspbench: warning: " << scene.name << ": of " << s.faces_read << " faces, " << s.triangulated
            << " triangulated (non-convex or non-planar), " << s.dropped_degenerate << " dropped (zero area), "
            << s.dropped_duplicate_vertex << " dropped (repeated vertex)\n";
}

}  // namespace

Scene scene_from_args(Args& args, std::uint64_t& seed) {
  const auto input = args.option("--input");
  const auto name = args.option("--scene");
  const auto n = args.option("--n");
  const auto seed_value = args.integer("--seed", 0, 9'000'000'000'000'000LL);
  const auto extra = args.options("--scene-param");
  seed = seed_value ? static_cast<std::uint64_t>(*seed_value) : 1;
  if (input && name) throw UsageError("give either --scene or --input, not both");
  if (input) {
    if (n || !extra.empty()) throw UsageError("--n and --scene-param apply to --scene, not --input");
    Scene scene = read_mesh(*input);
    warn_about_load(scene);
    return scene;
  }
  if (!name) throw UsageError("missing --scene NAME or --input FILE");
  ParamAssignments given;
  if (n) given.emplace_back("n", *n);
  // A mesh has no seed; --seed then only feeds the heuristic.
  if (seed_value && !is_mesh_scene(*name)) given.emplace_back("seed", std::to_string(*seed_value));
  for (const auto& kv : extra) given.push_back(parse_assignment(kv));
  Scene scene = make_scene(*name, given);
  check_scene(scene, "scene " + scene.name);
  warn_about_load(scene);
  return scene;
}

TreeArgs tree_args_from(Args& args, std::uint64_t seed) {
  TreeArgs t;
  t.seed = seed;
  t.options = build_options_from(args, seed);
  const auto heuristic = args.option("--heuristic");
  const auto params = args.options("--param");
  if (t.options.incremental) {
    if (heuristic || !params.empty())
      throw UsageError("--incremental consults no heuristic (the insertion order picks the planes); drop --heuristic");
    t.heuristic = kIncrementalLabel;
    return t;
  }
  if (!heuristic) throw UsageError("missing option --heuristic");
  t.heuristic = *heuristic;
  for (const auto& kv : params) t.params.push_back(parse_assignment(kv));
  experiments::params_of(t.heuristic);
  return t;
}

Shape shape_from(Args& args) {
  const std::string name = args.option("--shape").value_or("strict");
  const auto shape = shape_named(name);
  if (!shape) throw UsageError("--shape must be strict, coarse or leafy, not '" + name + "'");
  return *shape;
}

BuildOptions build_options_from(Args& args, std::uint64_t seed) {
  BuildOptions options;
  options.shape = shape_from(args);
  options.incremental = args.flag("--incremental");
  const auto order = args.option("--order");
  if (order && !options.incremental) throw UsageError("--order applies to --incremental builds");
  if (order && *order != "given" && *order != "shuffled")
    throw UsageError("--order must be given or shuffled, not '" + *order + "'");
  options.order = order == "shuffled" ? InsertOrder::Shuffled : InsertOrder::Given;
  options.order_seed = insertion_order_seed(seed);
  if (options.incremental && options.shape == Shape::Leafy) throw UsageError("--shape leafy builds recursively: drop --incremental");
  return options;
}

Scene scene_or_file(const std::string& spec, const std::vector<std::string>& params, std::string_view option) {
  const bool named = is_mesh_scene(spec) ||
                     std::any_of(generators().begin(), generators().end(), [&](const auto& g) { return g.name == spec; });
  Scene scene;
  if (named) {
    ParamAssignments given;
    for (const auto& kv : params) given.push_back(parse_assignment(kv));
    scene = make_scene(spec, given);
  } else {
    if (!params.empty()) throw UsageError(std::string(option) + " applies to a scene, not to the file " + spec);
    if (!std::filesystem::exists(spec)) throw UsageError("'" + spec + "' is neither a scene (bspbench scenes) nor a file");
    scene = read_mesh(spec);
  }
  check_scene(scene, scene.name);
  return scene;
}

Tree build_from_args(const Scene& scene, const TreeArgs& t) {
  if (t.options.incremental) return experiments::build_drawing(scene.polygons, nullptr, t.options);
  return experiments::HeuristicChoice::of(t.heuristic, t.params).build(scene.polygons, t.options, t.seed);
}

Kernel kernel_from(Args& args, const TreeArgs& t, const Scene& scene) {
  const std::string name = args.option("--kernel").value_or("float");
  const auto kernel = kernel_named(name);
  if (!kernel) throw UsageError("--kernel must be float or exact, not '" + name + "'");
  if (*kernel == Kernel::Exact && (t.options.incremental || t.options.shape == Shape::Leafy))
    throw UsageError("--kernel exact builds strict and coarse trees recursively: drop --incremental and --shape leafy");
  if (*kernel == Kernel::Exact && all_segments(scene.polygons))
    throw UsageError("--kernel exact builds 3D scenes; this one is 2D segments");
  return *kernel;
}

ExactTree build_exact_from_args(const Scene& scene, const TreeArgs& t) {
  const auto splitter = experiments::HeuristicChoice::of(t.heuristic, t.params).splitter(t.seed);
  return build_exact_tree(scene.polygons, *splitter, t.options);
}

nlohmann::json describe_run(const Scene& scene, const TreeArgs& t) {
  const nlohmann::json s = scene_json(scene);
  const nlohmann::json params = t.options.incremental
                                    ? nlohmann::json::object()
                                    : ParamSet::resolve(experiments::params_of(t.heuristic), t.params, t.heuristic).to_json();
  nlohmann::json out = {{"scene", scene.name},
          {"scene_params", s["params"]},
          {"scene_hash", s["hash"]},
          {"scene_bounds", s["bounds"]},
          {"heuristic", t.heuristic},
          {"heuristic_params", params},
          {"shape", shape_name(t.options.shape)},
          {"build", t.options.incremental ? "incremental" : "recursive"},
          {"order", t.options.order == InsertOrder::Shuffled ? "shuffled" : "given"},
          {"seed", t.seed}};
  if (t.kernel != Kernel::Float) out["kernel"] = kernel_name(t.kernel);
  return out;
}

}  // namespace bsp::cli
