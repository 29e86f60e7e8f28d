// bspbench_bench: every heuristic x scene x size, five benchmarks per tree, registered at run time
// so heuristics and generators added to the registries are measured without further wiring:
//   build/SCENE/n:N/HEURISTIC            build_tree; items = input polygons
//   traverse/SCENE/n:N/HEURISTIC         full back-to-front traversal from the 8 metric views; items = fragments emitted
//   traverse_culled/SCENE/n:N/HEURISTIC  the same culled by each view's frustum; items = fragments emitted
//   rays/SCENE/n:N/HEURISTIC             shoot_ray over 1000 metric rays; items = rays
//   validate/SCENE/n:N/HEURISTIC         validate_tree with one view (Embree); items = rays cast
// Counters: every deterministic tree metric. Default size 1000, seed 1; see bench_common.h for
// --bsp_scenes, --bsp_heuristics, --bsp_sizes and --benchmark_filter, e.g.
//   build/bench/bspbench_bench --bsp_scenes=city --bsp_sizes=1000,10000 --benchmark_filter='^build/'
#include <iostream>

#include "bench_common.h"
#include "common/errors.h"
#include "metrics/ray_cost.h"
#include "metrics/traversal_cost.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"
#include "tree/traverse_culled.h"
#include "validate/order_check.h"

namespace bsp::bench {

namespace {

constexpr std::uint32_t kRays = 1000;  // as MetricsSettings' default

void bm_traverse_culled(benchmark::State& state, const Scene* s, std::string h) {
  const Tree& t = tree(*s, h, kSeed);
  const auto views = metric_views(t.bounds, kViews);
  std::int64_t emitted = 0;
  for (auto _ : state)
    for (const auto& v : views) emitted += traverse_culled(t, v, [](std::uint32_t) {}).fragments_emitted;
  state.SetItemsProcessed(emitted);
  set_tree_counters(state);
}

void bm_rays(benchmark::State& state, const Scene* s, std::string h) {
  const Tree& t = tree(*s, h, kSeed);
  const auto rays = metric_rays(t.bounds, kRays, kSeed);
  for (auto _ : state)
    for (const auto& r : rays) benchmark::DoNotOptimize(shoot_ray(t, r).hit);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rays.size()));
  set_tree_counters(state);
}

void bm_validate(benchmark::State& state, const Scene* s, std::string h) {
  const Tree& t = tree(*s, h, kSeed);
  ValidationSettings settings;
  settings.views = 1;
  std::int64_t rays = 0, violations = 0;
  for (auto _ : state) {
    const ValidationReport r = validate_tree(t, settings);
    rays += static_cast<std::int64_t>(r.rays);
    violations = static_cast<std::int64_t>(r.violations);
  }
  state.SetItemsProcessed(rays);
  set_tree_counters(state);
  state.counters["validation_violations"] = static_cast<double>(violations);
}

void register_all(const Selection& sel) {
  using Fn = void (*)(benchmark::State&, const Scene*, std::string);
  const std::pair<const char*, Fn> kinds[] = {{"build", bm_build},
                                              {"traverse", bm_traverse},
                                              {"traverse_culled", bm_traverse_culled},
                                              {"rays", bm_rays},
                                              {"validate", bm_validate}};
  for (const auto& name : sel.scenes)
    for (auto n : sel.sizes) {
      const Scene* s = &scene(name, {{"n", std::to_string(n)}, {"seed", std::to_string(kSeed)}});
      for (const auto& h : sel.heuristics)
        for (const auto& [kind, fn] : kinds) {
          const std::string label = std::string(kind) + "/" + name + "/n:" + std::to_string(n) + "/" + h;
          benchmark::RegisterBenchmark(label.c_str(), fn, s, h)->Unit(benchmark::kMillisecond)->UseRealTime();
        }
    }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel = bsp::bench::take_selection(argc, argv, {{}, {}, {1000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench");
  } catch (const std::exception& e) {  // UsageError for a bad name or size
    std::cerr << "bspbench_bench: " << e.what() << "\n";
    return 2;
  }
}
