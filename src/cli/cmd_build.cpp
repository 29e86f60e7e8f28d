// bspbench build: build one tree and print its metrics, query costs included.
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/metrics_args.h"
#include "cli/run_args.h"
#include "experiments/draw/draw.h"
#include "metrics/kernel_stats.h"

namespace bsp::cli {

namespace {

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  Scene scene = scene_from_args(args, seed);
  TreeArgs t = tree_args_from(args, seed);
  t.kernel = kernel_from(args, t, scene);
  const MetricsSettings settings = metrics_settings_from(args, seed);
  args.finish();
  nlohmann::json out = describe_run(scene, t);
  if (t.kernel == Kernel::Exact) {
    // The measures read the exact tree's view (vertices from planes); "exact" says what the kernel did.
    const ExactTree tree = build_exact_from_args(scene, t);
    out.update(to_json(experiments::measure_drawing(tree.tree, scene.polygons, settings)));
    out["exact"] = to_json(tree.exact);
  } else {
    const Tree tree = build_from_args(scene, t);
    out.update(to_json(experiments::measure_drawing(tree, scene.polygons, settings)));
  }
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
  return 0;
}

}  // namespace

Command build_command() {
  static const std::string usage =
      std::string(kSceneUsage) + " " + std::string(kTreeUsage) + " " + std::string(kKernelUsage) + " " +
      std::string(kMetricsUsage) + " [--json]";
  return {"build", usage, "build a tree and print its metrics", run,
          concat({kSceneOptions, kTreeOptions, {kKernelOption}, kMetricsOptions, kJsonOption})};
}

}  // namespace bsp::cli
