// bspbench occlude: occlusion culling by beam tracing (cull/occlusion.h) from one eye or from the
// metric views, each view's output proved conservative by Embree primary rays
// (validate/occlusion_check.h) and compared with frustum culling alone. Exit code 1 when any view
// misses a fragment Embree sees.
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/cpu_time.h"
#include "common/errors.h"
#include "cull/occlusion.h"
#include "metrics/traversal_cost.h"
#include "experiments/occlude/occlusion_run.h"

namespace bsp::cli {

namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;

// An eye given on the command line looks at the scene box's centre unless told otherwise, with a
// 90° x 60° field of view reaching two box diagonals.
Frustum view_from(const Box& box, const Vec3& eye, std::optional<Vec3> look, double fov_x, double fov_y) {
  Frustum f;
  f.eye = eye;
  f.look = look.value_or(box.center() - eye);
  if (length(f.look) == 0) throw UsageError("the view direction (--look, or the eye to the box centre) is zero");
  f.look = normalize(f.look);
  f.up = std::abs(f.look.z) > 0.99 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  f.fov_x = fov_x;
  f.fov_y = fov_y;
  const double d = std::max(box.diagonal(), 1e-9);
  f.near = 1e-3 * d;
  f.far = 2 * d + length(eye - box.center());
  return f;
}

int run(Args& args) {
  std::uint64_t seed = 1;
  const bool json = args.flag("--json");
  const std::optional<Vec3> eye = args.point("--eye");
  const std::optional<Vec3> look = args.point("--look");
  const double fov_x = args.real("--fov").value_or(90.0) * kDegrees;
  const double fov_y = args.real("--fov-y").value_or(60.0) * kDegrees;
  const auto views = static_cast<std::uint32_t>(args.integer("--views", 1, 1000).value_or(4));
  OcclusionCheckSettings check;
  check.grid = static_cast<int>(args.integer("--grid", 1, 4096).value_or(check.grid));
  Scene scene = scene_from_args(args, seed);
  const TreeArgs t = tree_args_from(args, seed);
  args.finish();
  if (look && !eye) throw UsageError("--look needs --eye");
  if (!(fov_x > 0 && fov_x < 180 * kDegrees && fov_y > 0 && fov_y < 180 * kDegrees))
    throw UsageError("--fov and --fov-y want degrees in (0, 180)");
  const Tree tree = build_from_args(scene, t);
  const double setup_start = thread_cpu_seconds();
  const Occluder occluder(tree);
  const double setup_seconds = thread_cpu_seconds() - setup_start;
  const std::vector<Frustum> frusta =
      eye ? std::vector<Frustum>{view_from(tree.bounds, *eye, look, fov_x, fov_y)} : metric_views(tree.bounds, views);
  bool ok = true;
  nlohmann::json per_view = nlohmann::json::array();
  for (const Frustum& f : frusta) per_view.push_back(experiments::occlusion_view(tree, occluder, f, check, ok));
  nlohmann::json out = describe_run(scene, t);
  out["fragments"] = tree.fragments.size();
  out["subtree_bounds_cpu_seconds"] = setup_seconds;
  out["views"] = per_view;
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    std::cout << tree.fragments.size() << " fragments\n";
    for (const auto& v : per_view)
      std::cout << "eye " << v["eye"].dump() << ": emitted " << v["emitted"] << ", frustum-culled " << v["frustum_culled"]
                << ", seen by Embree " << v["seen_by_embree"] << ", missed " << v["missed_fragments"] << "\n";
  }
  return ok ? 0 : 1;
}

}  // namespace

Command occlude_command() {
  static const std::string usage = std::string(kSceneUsage) + " " + std::string(kTreeUsage) +
                                   " [--eye X,Y,Z [--look X,Y,Z] [--fov DEG] [--fov-y DEG] | --views V] [--grid G] [--json]";
  return {"occlude", usage,
          "occlusion culling by beam tracing from an eye (or the metric views), proved conservative by Embree",
          run,
          concat({kSceneOptions, kTreeOptions,
                  {{"--eye X,Y,Z", "the eye (default: the metric views of traversal cost)"},
                   {"--look X,Y,Z", "viewing direction (default: towards the scene box's centre)"},
                   {"--fov DEG", "horizontal field of view with --eye (default 90)"},
                   {"--fov-y DEG", "vertical field of view with --eye (default 60)"},
                   {"--views V", "without --eye: this many metric views (default 4)"},
                   {"--grid G", "Embree proof rays per side of the pixel grid (default 64), besides rays "
                                "through every fragment's sample points"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
