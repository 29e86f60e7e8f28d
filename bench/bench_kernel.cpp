// bspbench_bench_kernel: what exactness costs, the exact kernel's build beside the float kernel's
// on the same scene, in the same benchmark, on one thread:
//   kernel/SCENE/n:N/HEURISTIC   one iteration = one float build then one exact build (alternated,
//       so both see the same state of the machine); items = input polygons; counters:
//       float_seconds, exact_seconds: medians over the iterations (exact: snapping to frozen tree,
//           without the view's vertices); exact_vs_float: their ratio;
//       view_seconds: median time to compute the exact tree's vertices for output;
//       snap_seconds, load_seconds, choose_seconds: medians of the exact build's stages (ExactBuildStats);
//       filter_rate: side tests the floating-point filter decided, of all (tree/exact_build.h);
//       exact_tests, on_grid_tests: the others, decided in wide integers and at input corners;
//       float_fragments, exact_fragments; float_dropped: slivers and inputs the float kernel dropped.
// Select scenes, sizes and heuristics with --bsp_scenes, --bsp_sizes and --bsp_heuristics.
#include <omp.h>

#include <iostream>
#include <vector>

#include "bench_common.h"
#include "metrics/statistics.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/exact_build.h"

namespace bsp::bench {

namespace {

void bm_kernel(benchmark::State& state, const Scene* s, std::string heuristic) {
  omp_set_num_threads(1);
  std::vector<double> float_times, exact_times, view_times, snap_times, load_times, choose_times;
  ExactBuildStats stats;
  std::uint64_t float_fragments = 0, exact_fragments = 0, float_dropped = 0;
  for (auto _ : state) {
    {
      auto splitter = make_splitter(heuristic, {}, kSeed);
      const auto start = std::chrono::steady_clock::now();
      const Tree t = build_tree(s->polygons, *splitter);
      float_times.push_back(seconds_since(start));
      float_fragments = t.fragments.size();
      float_dropped = t.stats.dropped_slivers + t.stats.dropped_input;
    }
    auto splitter = make_splitter(heuristic, {}, kSeed);
    const ExactTree t = build_exact_tree(s->polygons, *splitter);
    exact_times.push_back(t.tree.stats.build_seconds);
    view_times.push_back(t.exact.view_seconds);
    snap_times.push_back(t.exact.snap_seconds);
    load_times.push_back(t.exact.load_seconds);
    choose_times.push_back(t.tree.stats.choose_seconds);
    stats = t.exact;
    exact_fragments = t.fragments.size();
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s->polygons.size()));
  const double f = median(float_times), e = median(exact_times);
  const ExactSideCounters& c = stats.sides;
  const double tests = static_cast<double>(c.predicates.filtered + c.predicates.exact + c.on_grid);
  state.counters["float_seconds"] = f;
  state.counters["exact_seconds"] = e;
  state.counters["exact_vs_float"] = e / f;
  state.counters["view_seconds"] = median(view_times);
  state.counters["snap_seconds"] = median(snap_times);
  state.counters["load_seconds"] = median(load_times);
  state.counters["choose_seconds"] = median(choose_times);
  state.counters["filter_rate"] = tests > 0 ? static_cast<double>(c.predicates.filtered) / tests : 1.0;
  state.counters["exact_tests"] = static_cast<double>(c.predicates.exact);
  state.counters["on_grid_tests"] = static_cast<double>(c.on_grid);
  state.counters["float_fragments"] = static_cast<double>(float_fragments);
  state.counters["exact_fragments"] = static_cast<double>(exact_fragments);
  state.counters["float_dropped"] = static_cast<double>(float_dropped);
}

void register_all(const Selection& sel) {
  for (const auto& name : sel.scenes)
    for (auto n : sel.sizes) {
      const Scene* s = &scene(name, {{"n", std::to_string(n)}});
      for (const auto& h : sel.heuristics) {
        const std::string label = "kernel/" + name + "/n:" + std::to_string(n) + "/" + h;
        benchmark::RegisterBenchmark(label.c_str(), bm_kernel, s, h)->Unit(benchmark::kMillisecond)->UseRealTime();
      }
    }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel =
        bsp::bench::take_selection(argc, argv, {{"random-disjoint", "near-degenerate"}, {"crystal"}, {10000, 100000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_kernel");
  } catch (const std::exception& e) {
    std::cerr << "bspbench_bench_kernel: " << e.what() << "\n";
    return 2;
  }
}
