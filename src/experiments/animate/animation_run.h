#pragma once
// One animation run, shared by `bspbench animate` and the sweep's animate jobs: an animated scene
// (generators/animation.h) kept as one tree by an update strategy (dynamic/updater.h), frame by
// frame. Each checked frame's tree must pass the invariants and the Embree order check; every frame
// reports its update's CPU time and work, the tree's size and depth, and the culled traversal's
// cost from fixed views of the static box; every drift_every-th frame (and the last) is also built
// from scratch, to measure how far the updated tree has drifted from a fresh one.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "animation.h"
#include "dynamic/updater.h"
#include "validate/view_rays.h"

namespace bsp::experiments {

struct AnimationRunSettings {
  ValidationSettings views;        // views = 0: invariants only
  std::uint32_t check_every = 1;   // check every N-th frame and the last
  std::uint32_t drift_every = 0;   // 0: no fresh builds
  // The in-run reference (experiments/timing.h), timed as one batch just before each update; none
  // when empty.
  std::function<void()> reference;
};

struct AnimationRun {
  // {frames, frames_checked, order_violations, invariant_violations, start_cpu_seconds,
  // update_cpu_seconds_median, update_cpu_seconds_max, fragments_first, fragments_last,
  // fragments_median, culled_nodes_visited_median, update_work_total, drift_last}
  nlohmann::json summary;
  nlohmann::json per_frame;
  std::vector<double> update_seconds;     // thread CPU seconds of each update, frames 1 on
  std::vector<double> reference_seconds;  // per update: CPU seconds per run of the reference before it
};

// `fresh_splitter` makes the splitter of each fresh build; `build` its options.
AnimationRun run_animation(const Animation& animation, Updater& updater,
                           const std::function<std::unique_ptr<Splitter>()>& fresh_splitter, const BuildOptions& build,
                           const AnimationRunSettings& settings);

}  // namespace bsp::experiments
