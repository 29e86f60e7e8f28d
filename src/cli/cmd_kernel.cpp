// bspbench kernel: the float and the exact kernel on the same scene snapped to its grid, side by
// side (experiments/kernel/kernel.h, the run a suite's "kernels" block makes): size, shape, what the
// tolerance dropped, both orders checked, classifications that differ, predicates, build times.
// Exit code 1 when the exact tree's order or either tree's invariants fail.
#include <cstdio>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "experiments/kernel/kernel.h"
#include "geometry/segment2.h"
#include "experiments/heuristic_choice.h"

namespace bsp::cli {

namespace {

std::string short_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  experiments::KernelSettings settings;
  settings.views = static_cast<std::uint32_t>(
      args.integer("--views", 1, experiments::kMaxViews).value_or(experiments::kKernelViews));
  settings.plane_eps_relative = args.real("--plane-eps").value_or(kPlaneEpsRelative);
  settings.perturbation = args.real("--perturb").value_or(0.0);
  if (!(settings.plane_eps_relative >= experiments::kMinRelative && settings.plane_eps_relative <= experiments::kMaxRelative))
    throw UsageError("--plane-eps wants a value in [" + short_text(experiments::kMinRelative) + ", " +
                     short_text(experiments::kMaxRelative) + "] (of the scene's diagonal)");
  if (!(settings.perturbation >= 0 && settings.perturbation <= experiments::kMaxRelative))
    throw UsageError("--perturb wants a value in [0, " + short_text(experiments::kMaxRelative) +
                     "] (of the scene's diagonal)");
  Scene scene = scene_from_args(args, seed);
  TreeArgs t = tree_args_from(args, seed);
  if (t.options.incremental || t.options.shape != Shape::Strict)
    throw UsageError("kernel compares strict recursive builds: drop --incremental and --shape");
  settings.seed = seed;
  args.finish();
  if (all_segments(scene.polygons)) throw UsageError("kernel compares 3D scenes; this one is 2D segments");
  const auto float_splitter = experiments::per_node_splitter(t.heuristic, t.params, t.seed);
  const auto exact_splitter = experiments::per_node_splitter(t.heuristic, t.params, t.seed);
  const experiments::KernelComparison c =
      experiments::compare_kernels(scene.polygons, *float_splitter, *exact_splitter, settings);
  nlohmann::json out = describe_run(scene, t);
  out["plane_eps_relative"] = settings.plane_eps_relative;
  out["perturbation"] = settings.perturbation;
  out["metrics"] = c.metrics;
  out["invariants"] = c.invariants;
  out["validation"] = c.validation;
  out["timings"] = c.timings;
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
  const bool ok = c.validation["violations"] == 0 && c.invariants["violations"] == 0;
  return ok ? 0 : 1;
}

}  // namespace

Command kernel_command() {
  static const std::string usage = std::string(kSceneUsage) +
                                   " --heuristic NAME [--param k=v]... [--views K] [--plane-eps E] [--perturb P] [--json]";
  return {"kernel", usage, "compare the float and the exact kernel on one scene snapped to its grid", run,
          concat({kSceneOptions,
                  {{"--heuristic NAME", "the splitting-plane heuristic (bspbench heuristics lists them)"},
                   {"--param k=v", "set a heuristic parameter; repeatable"},
                   {"--views K", "eyes each tree's order is checked from (default 4)"},
                   {"--plane-eps E", "the float kernel's tolerance, of the scene's diagonal (default 1e-9)"},
                   {"--perturb P", "move each input vertex by up to P of the diagonal per coordinate first (default 0)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
