// bspbench validate: build a tree and check its back-to-front orders from several eyes against
// Embree ray casts (validate/order_check.h; with --kernel exact, validate/exact_order_check.h); a 2D
// scene's segments as walls seen from eyes in its plane. Exit code 1 when any pair is drawn in the
// wrong order.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "geometry/segment2.h"
#include "common/errors.h"
#include "metrics/kernel_stats.h"
#include "validate/exact_order_check.h"
#include "validate/order_check.h"

namespace bsp::cli {

namespace {

// Upper bound of --views: each view casts a ray set over the whole scene.
constexpr long long kMaxViews = 1000;

void print(const nlohmann::json& out, bool json) {
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
}

// The exact kernel's tree, its order from each eye snapped to the grid, every hit decided exactly.
int run_exact(const Scene& scene, const TreeArgs& t, const ValidationSettings& settings, bool json) {
  const ExactTree tree = build_exact_from_args(scene, t);
  const ExactValidationReport report = validate_exact_tree(tree, settings);
  nlohmann::json out = describe_run(scene, t);
  out.update(to_json(report));
  out["exact"] = to_json(tree.exact);
  print(out, json);
  return report.report.ok() ? 0 : 1;
}

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  ValidationSettings settings;
  settings.views = static_cast<int>(args.integer("--views", 1, kMaxViews).value_or(settings.views));
  Scene scene = scene_from_args(args, seed);
  TreeArgs t = tree_args_from(args, seed);
  t.kernel = kernel_from(args, t, scene);
  args.finish();
  if (t.kernel == Kernel::Exact) return run_exact(scene, t, settings, json);
  const Tree tree = build_from_args(scene, t);
  const ValidationReport report = all_segments(scene.polygons)
                                      ? validate_segment_tree(tree, validation_eyes(tree.bounds, settings.views), settings)
                                      : validate_tree(tree, settings);
  nlohmann::json out = describe_run(scene, t);
  out.update(to_json(report));
  print(out, json);
  return report.ok() ? 0 : 1;
}

}  // namespace

Command validate_command() {
  static const std::string usage =
      std::string(kSceneUsage) + " " + std::string(kTreeUsage) + " " + std::string(kKernelUsage) + " [--views K] [--json]";
  return {"validate", usage, "check a tree's back-to-front orders from several eyes against Embree ray casts", run,
          concat({kSceneOptions, kTreeOptions, {kKernelOption}, {{"--views K", "eyes to check the order from (default 8)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
