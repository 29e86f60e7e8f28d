// bspbench validate: build a tree and check its back-to-front orders from several eyes against
// Embree ray casts (validate/order_check.h); a 2D scene's segments as walls seen from eyes in its plane. Exit code 1 when any pair is drawn in the wrong order.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "geometry/segment2.h"
#include "validate/order_check.h"

namespace bsp::cli {

namespace {

// Upper bound of --views: each view casts a ray set over the whole scene.
constexpr long long kMaxViews = 1000;

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  ValidationSettings settings;
  settings.views = static_cast<int>(args.integer("--views", 1, kMaxViews).value_or(settings.views));
  Scene scene = scene_from_args(args, seed);
  const TreeArgs t = tree_args_from(args, seed);
  args.finish();
  const Tree tree = build_from_args(scene, t);
  const ValidationReport report = all_segments(scene.polygons)
                                      ? validate_segment_tree(tree, validation_eyes(tree.bounds, settings.views), settings)
                                      : validate_tree(tree, settings);
  nlohmann::json out = describe_run(scene, t);
  out.update(to_json(report));
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
  return report.ok() ? 0 : 1;
}

}  // namespace

Command validate_command() {
  static const std::string usage = std::string(kSceneUsage) + " " + std::string(kTreeUsage) + " [--views K] [--json]";
  return {"validate", usage, "check a tree's back-to-front orders from several eyes against Embree ray casts", run,
          concat({kSceneOptions, kTreeOptions, {{"--views K", "eyes to check the order from (default 8)"}}, kJsonOption})};
}

}  // namespace bsp::cli
