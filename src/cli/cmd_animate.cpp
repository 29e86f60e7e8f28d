// bspbench animate: a static scene with moving solids (generators/animation.h) kept as one tree
// frame by frame by an update strategy (dynamic/updater.h); every checked frame's back-to-front
// orders are validated against Embree and its tree's invariants checked. Each frame reports its
// update's CPU time, the tree's size and depth, and the culled traversal's cost from fixed views of
// the static box. Exit code 1 when any frame fails either check.
#include <algorithm>
#include <iostream>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "animation.h"
#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "dynamic/updater.h"
#include "experiments/heuristic_choice.h"
#include "experiments/animate/animation_run.h"

namespace bsp::cli {

namespace {

constexpr long long kMaxViews = 100;

// With --input FILE the static scene is the file's polygons, which take no generator parameters.
AnimationSpec spec_from(Args& args, std::uint64_t seed, const std::optional<std::string>& input) {
  AnimationSpec s;
  if (input && args.option("--scene")) throw UsageError("give --scene or --input, not both");
  s.scene = input ? *input : args.required("--scene");
  for (const auto& kv : args.options("--scene-param")) s.scene_params.push_back(parse_assignment(kv));
  if (const auto n = args.option("--n")) s.scene_params.emplace_back("n", *n);
  if (input && !s.scene_params.empty()) throw UsageError("--n and --scene-param set a generator, not --input");
  s.moving = static_cast<std::uint32_t>(args.integer("--moving", 0, 1000).value_or(s.moving));
  s.frames = static_cast<std::uint32_t>(args.integer("--frames", 1, 100000).value_or(s.frames));
  s.object = args.option("--object").value_or(s.object);
  s.object_n = static_cast<std::uint64_t>(args.integer("--object-n", 1, 100000).value_or(static_cast<long long>(s.object_n)));
  s.size = args.real("--size").value_or(s.size);
  s.speed = args.real("--speed").value_or(s.speed);
  s.spin = args.real("--spin").value_or(s.spin);
  s.seed = seed;
  return s;
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const auto seed = static_cast<std::uint64_t>(args.integer("--seed", 0, 9'000'000'000'000'000LL).value_or(1));
  const std::optional<std::string> input = args.option("--input");
  AnimationSpec spec = spec_from(args, seed, input);
  const std::string heuristic = args.option("--heuristic").value_or("crystal");
  ParamAssignments params;
  for (const auto& kv : args.options("--param")) params.push_back(parse_assignment(kv));
  BuildOptions build;
  build.shape = shape_from(args);
  const std::string strategy = args.option("--strategy").value_or("rebuild");
  // Torres builds objects with halving planes; merge with the run's heuristic.
  const std::string object_heuristic =
      args.option("--object-heuristic").value_or(strategy == "torres" ? "halving" : heuristic);
  ParamAssignments object_params;
  for (const auto& kv : args.options("--object-param")) object_params.push_back(parse_assignment(kv));
  if (!args.option("--object-heuristic") && object_heuristic == heuristic) object_params = params;
  ValidationSettings views;
  views.views = static_cast<int>(args.integer("--views", 0, kMaxViews).value_or(2));
  const auto every = static_cast<std::uint32_t>(args.integer("--check-every", 1, 100000).value_or(1));
  const auto drift_every = static_cast<std::uint32_t>(args.integer("--drift-every", 0, 100000).value_or(0));
  args.finish();

  const Animation animation = input ? Animation(spec, scene_or_file(spec.scene, {}, "--input")) : Animation(spec);
  auto updater = make_updater(strategy, experiments::per_node_splitter(heuristic, params, seed),
                              experiments::per_node_splitter(object_heuristic, object_params, seed), build);
  experiments::AnimationRunSettings settings;
  settings.views = views;
  settings.check_every = every;
  settings.drift_every = drift_every;
  const experiments::AnimationRun run = experiments::run_animation(
      animation, *updater, [&] { return experiments::per_node_splitter(heuristic, params, seed); }, build, settings);
  nlohmann::json out = {{"animation", animation.describe()},
                        {"strategy", strategy},
                        {"heuristic", heuristic},
                        {"object_heuristic", object_heuristic},
                        {"views", views.views},
                        {"check_every", every},
                        {"drift_every", drift_every},
                        {"summary", run.summary}};
  if (json) {
    out["per_frame"] = run.per_frame;
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
  const auto& s = out["summary"];
  return s["order_violations"] == 0 && s["invariant_violations"] == 0 ? 0 : 1;
}

}  // namespace

Command animate_command() {
  return {"animate",
          "(--scene NAME [--n N] [--scene-param k=v]... | --input FILE) [--moving K] [--frames F] [--object SOLID] [--object-n N] "
          "[--size S] [--speed V] [--spin W] [--seed S] [--strategy rebuild|reinsert|reinsert-each|merge|torres] [--heuristic H] [--param k=v]... "
          "[--object-heuristic H] [--object-param k=v]... "
          "[--shape strict|coarse] [--views V] [--check-every N] [--drift-every N] [--json]",
          "keep a tree valid while solids move through a scene, frame by frame, each checked frame proved by Embree",
          run,
          concat({{{"--scene NAME", "the static scene (bspbench scenes) or mesh:NAME"},
                   {"--n N", "the static scene's polygon count parameter"},
                   {"--scene-param k=v", "another parameter of the static scene; repeatable"},
                   {"--moving K", "moving objects (default 4)"},
                   {"--frames F", "frames (default 100)"},
                   {"--object SOLID", "the moving objects' closed-solid generator (default sphere), or 'scene': groups of "
                                      "--object-n of the scene's own polygons, each taken out of the scene"},
                   {"--object-n N", "its polygon count parameter (default 80)"},
                   {"--size S", "object radius in box diagonals (default 0.04)"},
                   {"--speed V", "distance travelled per frame in box diagonals (default 0.004)"},
                   {"--spin W", "radians turned per frame (default 0.02)"},
                   {"--seed S", "seed of the scene, the paths and the heuristic (default 1)"},
                   {"--strategy NAME", "update strategy: rebuild (a full build per frame, the default), reinsert "
                                       "(remove all objects, then reinsert them), reinsert-each (one object at a "
                                       "time), merge (merge the objects' trees into the "
                                       "static tree), torres (object trees in cells, separating planes)"},
                   {"--heuristic H", "heuristic of the scene's builds (default crystal)"},
                   {"--param k=v", "a heuristic parameter; repeatable"},
                   {"--object-heuristic H", "heuristic of the objects' own trees, merge and torres (default: halving "
                                            "for torres, --heuristic for merge)"},
                   {"--object-param k=v", "a parameter of the object heuristic; repeatable"},
                   kBuildModeOptions[0],
                   {"--views V", "eyes of each checked frame's Embree order check (default 2; 0: invariants only)"},
                   {"--check-every N", "check every N-th frame and the last (default 1: every frame)"},
                   {"--drift-every N", "every N-th frame and the last, also build the frame from scratch and "
                                       "report the updated tree's size, depth and culled cost against it "
                                       "(default 0: never)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
