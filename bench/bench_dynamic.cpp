// bspbench_bench_dynamic: the per-frame update of a dynamic scene (src/dynamic) beside Embree's
// BVH build of the same frame, in the same run:
//   update/STRATEGY/SCENE/n:N/moving:K/HEURISTIC   one iteration = one frame's update (the frames
//       of the animation in turn, 4 spheres of 80 triangles by default, generators/animation.h);
//       items = the frame's polygons; counters:
//       update_seconds: median over the iterations; embree_bvh_seconds: median of Embree's MEDIUM
//           BVH build of frame 0's polygons on one thread (references.h), what an engine pays to
//           rebuild its hierarchy each frame; update_vs_embree: their ratio;
//       fragments: of the last frame's tree; moving_fraction: the moving share of the polygons.
// Select scenes, sizes and heuristics with --bsp_scenes, --bsp_sizes and --bsp_heuristics
// (bench_common.h); the strategies are every one dynamic/updater.h registers.
#include <iostream>
#include <vector>

#include "animation.h"
#include "bench_common.h"
#include "dynamic/updater.h"
#include "metrics/statistics.h"
#include "references.h"
#include "split/registry.h"

namespace bsp::bench {

namespace {

constexpr std::uint32_t kFrames = 64;
constexpr int kReferenceRepeats = 5;

AnimationSpec spec_for(const std::string& scene, std::uint64_t n, std::uint32_t moving) {
  AnimationSpec s;
  s.scene = scene;
  s.scene_params = {{"n", std::to_string(n)}};
  s.moving = moving;
  s.frames = kFrames;
  return s;
}

// The baseline in the same run: rebuild's median update over the same frames.
double rebuild_seconds(std::span<const Polygon> still, const std::vector<std::vector<Polygon>>& frames,
                       std::uint32_t moving, const std::string& heuristic) {
  auto rebuild = make_updater("rebuild", make_splitter(heuristic, {}, kSeed), make_splitter(heuristic, {}, kSeed));
  rebuild->start(still, frames[0], moving);
  std::vector<double> times;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const auto start = std::chrono::steady_clock::now();
    rebuild->update(frames[f]);
    times.push_back(seconds_since(start));
  }
  return median(times);
}

void bm_update(benchmark::State& state, std::string strategy, AnimationSpec spec, std::string heuristic) {
  const Animation animation(spec);
  const Scene frame0 = animation.frame(0);
  const std::span<const Polygon> still(frame0.polygons.data(), animation.static_scene().polygons.size());
  const auto first = static_cast<std::uint32_t>(still.size());
  std::vector<std::vector<Polygon>> frames;
  for (std::uint32_t f = 0; f < kFrames; ++f) frames.push_back(animation.moving_at(f, first));
  auto updater = make_updater(strategy, make_splitter(heuristic, {}, kSeed),
                              make_splitter(strategy == "torres" ? "halving" : heuristic, {}, kSeed));
  updater->start(still, frames[0], spec.moving);
  std::vector<double> times;
  std::uint32_t f = 0;
  for (auto _ : state) {
    f = (f + 1) % kFrames;
    const auto start = std::chrono::steady_clock::now();
    updater->update(frames[f]);
    times.push_back(seconds_since(start));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(frame0.polygons.size()));
  const double update = median(times);
  const double embree = embree_bvh_build_seconds(frame0.polygons, 1, kReferenceRepeats);
  const double rebuild = strategy == "rebuild" ? update : rebuild_seconds(still, frames, spec.moving, heuristic);
  state.counters["update_seconds"] = update;
  state.counters["rebuild_seconds"] = rebuild;
  state.counters["update_vs_rebuild"] = update / rebuild;
  state.counters["embree_bvh_seconds"] = embree;
  state.counters["update_vs_embree"] = update / embree;
  state.counters["fragments"] = static_cast<double>(updater->tree().fragments.size());
  state.counters["moving_fraction"] =
      static_cast<double>(animation.moving_polygons()) / static_cast<double>(frame0.polygons.size());
}

void register_all(const Selection& sel) {
  for (const auto& scene : sel.scenes)
    for (auto n : sel.sizes)
      for (std::uint32_t moving : {4u, 16u})
        for (const auto& h : sel.heuristics)
          for (const auto& strategy : updater_names()) {
            const std::string name = "update/" + strategy + "/" + scene + "/n:" + std::to_string(n) +
                                     "/moving:" + std::to_string(moving) + "/" + h;
            benchmark::RegisterBenchmark(name.c_str(), bm_update, strategy, spec_for(scene, n, moving), h)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
          }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel = bsp::bench::take_selection(argc, argv, {{"city", "architecture"}, {"crystal"}, {1000, 10000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_dynamic");
  } catch (const std::exception& e) {
    std::cerr << "bspbench_bench_dynamic: " << e.what() << "\n";
    return 2;
  }
}
