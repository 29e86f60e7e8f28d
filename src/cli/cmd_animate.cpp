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
#include "split/registry.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

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

// Views of the static scene's box (metric_views), the same for every frame so frames compare.
constexpr std::uint32_t kCostViews = 4;

// The same frame built from scratch with the run's heuristic, to measure how far an updated tree
// has drifted from a fresh one.
struct FreshBuild {
  std::uint64_t fragments = 0, nodes = 0, depth = 0;
  TraversalCost cost;
};

struct FrameRecord {
  UpdateWork work;
  std::uint64_t fragments = 0, nodes = 0, depth = 0, order_violations = 0, invariant_violations = 0;
  TraversalCost cost;
  bool checked = false;
  std::optional<FreshBuild> fresh;
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
  FrameRecord f{work, tree.fragments.size(), tree.nodes.size(), depth_of(tree), 0, 0, traversal_cost(tree, views), check, {}};
  if (!check) return f;
  f.invariant_violations = check_tree_invariants(tree, input).violations;
  if (settings.views > 0) f.order_violations = validate_tree(tree, settings).violations;
  return f;
}

// Updated against fresh, as ratios (1: no drift).
nlohmann::json drift_json(const FrameRecord& f) {
  const auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  return {{"fresh_fragments", f.fresh->fragments},
          {"fresh_nodes", f.fresh->nodes},
          {"fresh_depth", f.fresh->depth},
          {"fresh_culled_nodes_visited", f.fresh->cost.culled_nodes_visited},
          {"fragments_ratio", ratio(static_cast<double>(f.fragments), static_cast<double>(f.fresh->fragments))},
          {"nodes_ratio", ratio(static_cast<double>(f.nodes), static_cast<double>(f.fresh->nodes))},
          {"depth_ratio", ratio(static_cast<double>(f.depth), static_cast<double>(f.fresh->depth))},
          {"culled_nodes_visited_ratio", ratio(f.cost.culled_nodes_visited, f.fresh->cost.culled_nodes_visited)}};
}

nlohmann::json work_json(const UpdateWork& w) {
  return {{"polygons_built", w.polygons_built},
          {"nodes_built", w.nodes_built},
          {"fragments_removed", w.fragments_removed},
          {"nodes_removed", w.nodes_removed},
          {"repairs", w.repairs},
          {"reinserted_fragments", w.reinserted_fragments},
          {"dismantled_nodes", w.dismantled_nodes},
          {"fragments_inserted", w.fragments_inserted},
          {"partitioned_nodes", w.partitioned_nodes},
          {"moved_nodes", w.moved_nodes},
          {"objects_placed", w.objects_placed},
          {"objects_whole", w.objects_whole}};
}

void add(UpdateWork& to, const UpdateWork& w) {
  to.seconds += w.seconds;
  to.polygons_built += w.polygons_built;
  to.nodes_built += w.nodes_built;
  to.fragments_removed += w.fragments_removed;
  to.nodes_removed += w.nodes_removed;
  to.repairs += w.repairs;
  to.reinserted_fragments += w.reinserted_fragments;
  to.dismantled_nodes += w.dismantled_nodes;
  to.fragments_inserted += w.fragments_inserted;
  to.partitioned_nodes += w.partitioned_nodes;
  to.moved_nodes += w.moved_nodes;
  to.objects_placed += w.objects_placed;
  to.objects_whole += w.objects_whole;
}

// Frame 0 is the strategy's start (a whole build); the update figures are over frames 1 on.
nlohmann::json summary(const std::vector<FrameRecord>& frames) {
  std::vector<double> seconds, fragments, visited;
  std::uint64_t order = 0, invariants = 0, checked = 0;
  UpdateWork total;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameRecord& f = frames[i];
    if (i > 0) {
      seconds.push_back(f.work.seconds);
      add(total, f.work);
    }
    fragments.push_back(static_cast<double>(f.fragments));
    visited.push_back(f.cost.culled_nodes_visited);
    order += f.order_violations;
    invariants += f.invariant_violations;
    checked += f.checked;
  }
  nlohmann::json s = {{"frames", frames.size()},
                      {"frames_checked", checked},
                      {"order_violations", order},
                      {"invariant_violations", invariants},
                      {"start_cpu_seconds", frames.front().work.seconds},
                      {"fragments_first", frames.front().fragments},
                      {"fragments_last", frames.back().fragments},
                      {"fragments_median", median(fragments)},
                      {"culled_nodes_visited_median", median(visited)}};
  if (!seconds.empty()) {
    s["update_cpu_seconds_median"] = median(seconds);
    s["update_cpu_seconds_max"] = *std::max_element(seconds.begin(), seconds.end());
    s["update_work_total"] = work_json(total);
  }
  const FrameRecord* last_fresh = nullptr;
  for (const auto& f : frames)
    if (f.fresh) last_fresh = &f;
  if (last_fresh) s["drift_last"] = drift_json(*last_fresh);
  return s;
}

nlohmann::json frames_json(const std::vector<FrameRecord>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : frames)
    out.push_back({{"update_cpu_seconds", f.work.seconds},
                   {"work", work_json(f.work)},
                   {"fragments", f.fragments},
                   {"nodes", f.nodes},
                   {"depth", f.depth},
                   {"culled_nodes_visited", f.cost.culled_nodes_visited},
                   {"culled_fragments_emitted", f.cost.culled_fragments_emitted},
                   {"checked", f.checked},
                   {"drift", f.fresh ? drift_json(f) : nlohmann::json(nullptr)},
                   {"order_violations", f.order_violations},
                   {"invariant_violations", f.invariant_violations}});
  return out;
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
  auto updater = make_updater(strategy, make_splitter(heuristic, params, seed),
                              make_splitter(object_heuristic, object_params, seed), build);
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
    if (drift_every > 0 && (f % drift_every == 0 || f + 1 == spec.frames)) {
      const std::unique_ptr<Splitter> fresh_splitter = make_splitter(heuristic, params, seed);
      const Tree fresh = build_tree(input.polygons, *fresh_splitter, build);
      frames.back().fresh = FreshBuild{fresh.fragments.size(), fresh.nodes.size(), depth_of(fresh),
                                       traversal_cost(fresh, cost_views)};
    }
  }
  nlohmann::json out = {{"animation", animation.describe()},
                        {"strategy", strategy},
                        {"heuristic", heuristic},
                        {"object_heuristic", object_heuristic},
                        {"views", views.views},
                        {"check_every", every},
                        {"drift_every", drift_every},
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
                   {"--object SOLID", "the moving objects' closed-solid generator (default sphere)"},
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
