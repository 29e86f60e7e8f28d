#include "experiments/animate/animation_run.h"

#include <algorithm>
#include <optional>

#include "experiments/timing.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "tree/build.h"
#include "tree/depth.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

namespace bsp::experiments {

namespace {

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

FrameRecord check_frame(const Updater& u, const UpdateWork& work, std::span<const Polygon> input, bool check,
                        const ValidationSettings& settings, std::span<const Frustum> views) {
  const Tree& tree = u.tree();
  FrameRecord f{work, tree.fragments.size(), tree.nodes.size(), max_depth(tree), 0, 0, traversal_cost(tree, views), check, {}};
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

}  // namespace

AnimationRun run_animation(const Animation& animation, Updater& updater,
                           const std::function<std::unique_ptr<Splitter>()>& fresh_splitter, const BuildOptions& build,
                           const AnimationRunSettings& settings) {
  const AnimationSpec& spec = animation.spec();
  // The static polygons as every frame numbers them (Animation::frame), so the invariants' per-source
  // checks compare like with like.
  const Scene first = animation.frame(0);
  const std::span<const Polygon> still(first.polygons.data(), animation.static_scene().polygons.size());
  const std::vector<Frustum> cost_views = metric_views(bounds(animation.static_scene()), kCostViews);
  std::vector<FrameRecord> frames;
  std::vector<double> reference_seconds;
  for (std::uint32_t f = 0; f < spec.frames; ++f) {
    const Scene input = animation.frame(f);
    const auto moving = std::span<const Polygon>(input.polygons).subspan(still.size());
    if (f > 0 && settings.reference) reference_seconds.push_back(time_batch(settings.reference));
    const UpdateWork work = f == 0 ? updater.start(still, moving, spec.moving) : updater.update(moving);
    const bool last = f + 1 == spec.frames;
    frames.push_back(check_frame(updater, work, input.polygons, f % settings.check_every == 0 || last, settings.views,
                                 cost_views));
    if (settings.drift_every > 0 && (f % settings.drift_every == 0 || last)) {
      const std::unique_ptr<Splitter> splitter = fresh_splitter();
      const Tree fresh = build_tree(input.polygons, *splitter, build);
      frames.back().fresh = FreshBuild{fresh.fragments.size(), fresh.nodes.size(), max_depth(fresh),
                                       traversal_cost(fresh, cost_views)};
    }
  }
  AnimationRun run{summary(frames), frames_json(frames), {}, std::move(reference_seconds)};
  for (std::size_t f = 1; f < frames.size(); ++f) run.update_seconds.push_back(frames[f].work.seconds);
  return run;
}

}  // namespace bsp::experiments
