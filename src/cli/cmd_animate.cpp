// bspbench animate: a static scene with moving solids (generators/animation.h) kept as one tree
// frame by frame by an update strategy (dynamic/updater.h); every checked frame's back-to-front
// orders are validated against Embree and its tree's invariants checked. Each frame reports its
// update's CPU time, the tree's size and depth, and the culled traversal's cost from fixed views of
// the static box. Exit code 1 when any frame fails either check.
#include <algorithm>
#include <iostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "animation.h"
#include "cli/commands.h"
#include "cli/run_args.h"
#include "dynamic/updater.h"
#include "split/registry.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

namespace bsp::cli {

namespace {

constexpr long long kMaxViews = 100;

AnimationSpec spec_from(Args& args, std::uint64_t seed) {
  AnimationSpec s;
  s.scene = args.required("--scene");
  for (const auto& kv : args.options("--scene-param")) s.scene_params.push_back(parse_assignment(kv));
  if (const auto n = args.option("--n")) s.scene_params.emplace_back("n", *n);
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

// Views of the static scene's box (metric_views), the same for every frame so frames compare.
constexpr std::uint32_t kCostViews = 4;

struct FrameRecord {
  UpdateWork work;
  std::uint64_t fragments = 0, nodes = 0, depth = 0, order_violations = 0, invariant_violations = 0;
  TraversalCost cost;
  bool checked = false;
};

// The root has depth 1. Explicit stack: a frame's tree may be a chain.
std::uint64_t depth_of(const Tree& tree) {
  std::uint64_t depth = 0;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> stack;
  if (!tree.nodes.empty()) stack.push_back({0, 1});
  while (!stack.empty()) {
    const auto [r, d] = stack.back();
    stack.pop_back();
    depth = std::max(depth, d);
    for (const std::uint32_t c : {tree.nodes[r].front, tree.nodes[r].back})
      if (c != kNull) stack.push_back({c, d + 1});
  }
  return depth;
}

FrameRecord check_frame(const Updater& u, const UpdateWork& work, std::span<const Polygon> input, bool check,
                        const ValidationSettings& settings, std::span<const Frustum> views) {
  const Tree& tree = u.tree();
  FrameRecord f{work, tree.fragments.size(), tree.nodes.size(), depth_of(tree), 0, 0, traversal_cost(tree, views), check};
  if (!check) return f;
  f.invariant_violations = check_tree_invariants(tree, input).violations;
  if (settings.views > 0) f.order_violations = validate_tree(tree, settings).violations;
  return f;
}

nlohmann::json summary(const std::vector<FrameRecord>& frames) {
  std::vector<double> seconds, fragments, visited;
  std::uint64_t order = 0, invariants = 0, checked = 0;
  for (const auto& f : frames) {
    seconds.push_back(f.work.seconds);
    fragments.push_back(static_cast<double>(f.fragments));
    visited.push_back(f.cost.culled_nodes_visited);
    order += f.order_violations;
    invariants += f.invariant_violations;
    checked += f.checked;
  }
  return {{"frames", frames.size()},
          {"frames_checked", checked},
          {"order_violations", order},
          {"invariant_violations", invariants},
          {"update_cpu_seconds_median", median(seconds)},
          {"update_cpu_seconds_max", *std::max_element(seconds.begin(), seconds.end())},
          {"fragments_first", frames.front().fragments},
          {"fragments_last", frames.back().fragments},
          {"fragments_median", median(fragments)},
          {"culled_nodes_visited_median", median(visited)}};
}

nlohmann::json frames_json(const std::vector<FrameRecord>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : frames)
    out.push_back({{"update_cpu_seconds", f.work.seconds},
                   {"polygons_built", f.work.polygons_built},
                   {"fragments", f.fragments},
                   {"nodes", f.nodes},
                   {"depth", f.depth},
                   {"culled_nodes_visited", f.cost.culled_nodes_visited},
                   {"culled_fragments_emitted", f.cost.culled_fragments_emitted},
                   {"checked", f.checked},
                   {"order_violations", f.order_violations},
                   {"invariant_violations", f.invariant_violations}});
  return out;
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const auto seed = static_cast<std::uint64_t>(args.integer("--seed", 0, 9'000'000'000'000'000LL).value_or(1));
  AnimationSpec spec = spec_from(args, seed);
  const std::string heuristic = args.option("--heuristic").value_or("crystal");
  ParamAssignments params;
  for (const auto& kv : args.options("--param")) params.push_back(parse_assignment(kv));
  BuildOptions build;
  build.shape = shape_from(args);
  const std::string strategy = args.option("--strategy").value_or("rebuild");
  ValidationSettings views;
  views.views = static_cast<int>(args.integer("--views", 0, kMaxViews).value_or(2));
  const auto every = static_cast<std::uint32_t>(args.integer("--check-every", 1, 100000).value_or(1));
  args.finish();

  const Animation animation(spec);
  auto updater = make_updater(strategy, make_splitter(heuristic, params, seed), build);
  // The static polygons as every frame numbers them (Animation::frame), so the invariants' per-source
  // checks compare like with like.
  const Scene first = animation.frame(0);
  const std::span<const Polygon> still(first.polygons.data(), animation.static_scene().polygons.size());
  const std::vector<Frustum> cost_views = metric_views(bounds(animation.static_scene()), kCostViews);
  std::vector<FrameRecord> frames;
  for (std::uint32_t f = 0; f < spec.frames; ++f) {
    const Scene input = animation.frame(f);
    const auto moving = std::span<const Polygon>(input.polygons).subspan(still.size());
    const UpdateWork work = f == 0 ? updater->start(still, moving, spec.moving) : updater->update(moving);
    frames.push_back(
        check_frame(*updater, work, input.polygons, f % every == 0 || f + 1 == spec.frames, views, cost_views));
  }
  nlohmann::json out = {{"animation", animation.describe()},
                        {"strategy", strategy},
                        {"heuristic", heuristic},
                        {"views", views.views},
                        {"check_every", every},
                        {"summary", summary(frames)}};
  if (json) {
    out["per_frame"] = frames_json(frames);
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
          "--scene NAME [--n N] [--scene-param k=v]... [--moving K] [--frames F] [--object SOLID] [--object-n N] "
          "[--size S] [--speed V] [--spin W] [--seed S] [--strategy rebuild] [--heuristic H] [--param k=v]... "
          "[--shape strict|coarse] [--views V] [--check-every N] [--json]",
          "keep a tree valid while solids move through a scene, frame by frame, each checked frame proved by Embree",
          run,
          concat({{{"--scene NAME", "the static scene (bspbench scenes) or mesh:NAME"},
                   {"--n N", "the static scene's polygon count parameter"},
                   {"--scene-param k=v", "another parameter of the static scene; repeatable"},
                   {"--moving K", "moving objects (default 4)"},
                   {"--frames F", "frames (default 100)"},
                   {"--object SOLID", "the moving objects' closed-solid generator (default sphere)"},
                   {"--object-n N", "its polygon count parameter (default 80)"},
                   {"--size S", "object radius in box diagonals (default 0.04)"},
                   {"--speed V", "distance travelled per frame in box diagonals (default 0.004)"},
                   {"--spin W", "radians turned per frame (default 0.02)"},
                   {"--seed S", "seed of the scene, the paths and the heuristic (default 1)"},
                   {"--strategy NAME", "update strategy: rebuild (a full build per frame)"},
                   {"--heuristic H", "heuristic of every build (default crystal)"},
                   {"--param k=v", "a heuristic parameter; repeatable"},
                   kBuildModeOptions[0],
                   {"--views V", "eyes of each checked frame's Embree order check (default 2; 0: invariants only)"},
                   {"--check-every N", "check every N-th frame and the last (default 1: every frame)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
