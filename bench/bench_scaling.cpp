// bspbench_bench_scaling: build and back-to-front traversal at N = 10^4, 10^5, 10^6 on
// random-disjoint and sphere-field (scenes whose density stays the same as N grows), for every
// heuristic at its defaults, each beside its in-run reference (references.h):
//   scaling/build/SCENE/n:N/HEURISTIC/threads:T   T = 1 and 2; items = input polygons; counters:
//       the tree's metrics, embree_bvh_seconds (Embree's MEDIUM BVH of the same triangles on as
//       many threads as the build, built after each build), build_vs_embree (the median over the
//       runs of each build's time over the Embree build after it),
//       bytes_per_fragment (and its parts: position_, attribute_, record_, node_ and
//       plane_bytes_per_fragment, tree.h's TreeBytes), build_peak_vs_tree (how far resident
//       memory rose during one more build, the finished tree included, over the tree's bytes;
//       resident_memory.h); at T = 2
//       also speedup (the 1-thread median build time / this one's); and the build's bill
//       (BuildStats): at T = 1 choose_vs_embree (time inside the heuristic's choose) and
//       machinery_vs_embree (the build's own work: loading, partitioning, splitting, node emission,
//       layout, freezing), which add up to build_vs_embree; at T = 2 the same two as seconds of
//       thread time summed over the threads (choose_thread_seconds, machinery_thread_seconds);
//       at T = 1 visit_nanoseconds, the build time over the sum of the fragments' depths: the cost
//       of one fragment passing one level, which a build whose cost is its depth keeps flat in N;
//       and at T = 1 the rate of plane-side tests (BuildStats::side_tests) against this machine's
//       ceilings (roofline.h): side_tests, side_test_rate (all tests over the build's time),
//       choose_side_test_rate (the heuristic's tests over its choosing time), roofline_compute_rate
//       and roofline_memory_rate (tests per second one core's FMA rate allows, and its read
//       bandwidth when each test reads a 24-byte vertex), choose_rate_vs_compute (the choosing
//       rate over the compute ceiling).
//       Embree builds once after each build, untimed by the benchmark, and every ratio is the
//       median of the runs' ratios to it: a reference paired run by run, as the sweep's are
//   scaling/traverse/SCENE/n:N/HEURISTIC  back-to-front from the 8 metric views; items = fragments
//       emitted; counters: sort_seconds (std::sort of as many (depth, id) pairs as one view emits),
//       traverse_vs_sort (median time per view / that), traverse_vs_embree_rays (the median over
//       runs of each run's time per view / Embree's 64 x 64 primary rays per view timed right after
//       it: a paired reference that drifts with the machine as the traversal does, both reading a
//       hierarchy from memory)
// The ratios to medians come from the same benchmark, minutes apart at most; the paired ratio
// also cancels a machine whose speed for such code drifts within a run (gate-timing.md).
//
// random-triangles can be chosen too (--bsp_scenes=random-triangles): its `size` then shrinks as
// 0.1 * (1000 / N)^(1/3), the generator's default at N = 10^3, so each triangle overlaps about as
// many others at every N and the growth measured is the heuristic's, not the clutter's.
// Select with --bsp_scenes, --bsp_heuristics, --bsp_sizes (bench_common.h), e.g.
//   build/bench/bspbench_bench_scaling --bsp_heuristics=crystal --bsp_sizes=1000000
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>

#include <omp.h>

#include "bench_common.h"
#include "experiments/reference_build.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "references.h"
#include "resident_memory.h"
#include "roofline.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"

namespace bsp::bench {

namespace {

constexpr double kDefaultSize = 0.1;  // random-triangles' default `size`
constexpr double kDefaultN = 1000;    // the N at which it applies unchanged
constexpr int kReferenceRepeats = 5;  // timed runs of each reference; their median is used
// Primary rays per view side for the traversal's paired reference: 64^2 rays per view take about
// half as long as a back-to-front traversal of 10^5 fragments, long enough to time on its own.
constexpr int kRayGrid = 64;
// A build of 10^5 polygons takes up to a second and one of 10^6 seconds, so Google Benchmark's
// minimum time would allow one run, and a median of one is no median (one disturbed run then
// decides the gated ratio): from this size on, builds run a fixed number of times, and the median
// of 5 outvotes two disturbed runs.
constexpr std::uint64_t kFixedBuildRunsN = 100000;
constexpr benchmark::IterationCount kBuildRuns = 5;
// Runs of the 8 views at 10^6, where the library's minimum time would stop at one or two: the
// median of 5 is what the ratio to the sort's median of kReferenceRepeats is taken from.
constexpr std::uint64_t kFixedTraversalRunsN = 1000000;
constexpr benchmark::IterationCount kTraversalRuns = 5;

using Clock = std::chrono::steady_clock;

ParamAssignments scene_params(const std::string& name, std::uint64_t n) {
  ParamAssignments p = {{"n", std::to_string(n)}, {"seed", std::to_string(kSeed)}};
  if (name == "random-triangles") {
    char size[32];
    std::snprintf(size, sizeof size, "%.6g", kDefaultSize * std::cbrt(kDefaultN / static_cast<double>(n)));
    p.emplace_back("size", size);
  }
  return p;
}

// This machine's ceilings for side tests, measured once per run, on first use.
const Roofline& roofline() {
  static const Roofline measured = measure_roofline(kReferenceRepeats);
  return measured;
}

// The build's rate of plane-side tests on one thread against the machine's ceilings (roofline.h):
// all of them over the whole build, and the heuristic's over its choosing time; then the choosing
// rate as a fraction of the compute ceiling, the one bound every test is under whatever it reads.
void set_side_test_counters(benchmark::State& state, const BuildStats& stats, double build_seconds,
                            double choose_seconds) {
  const Roofline& r = roofline();
  state.counters["side_tests"] = static_cast<double>(stats.side_tests);
  state.counters["side_test_rate"] = static_cast<double>(stats.side_tests) / build_seconds;
  state.counters["roofline_compute_rate"] = r.compute_tests_per_second();
  state.counters["roofline_memory_rate"] = r.memory_tests_per_second();
  if (stats.choose_side_tests == 0 || choose_seconds <= 0) return;
  const double choose_rate = static_cast<double>(stats.choose_side_tests) / choose_seconds;
  state.counters["choose_side_test_rate"] = choose_rate;
  state.counters["choose_rate_vs_compute"] = choose_rate / r.compute_tests_per_second();
}

// Bytes per fragment of the tree, in all and part by part (TreeBytes).
void set_memory_counters(benchmark::State& state, const Tree& t) {
  if (t.fragments.empty()) return;
  const TreeBytes b = t.bytes_by_part();
  const auto per_fragment = [&](std::size_t bytes) {
    return static_cast<double>(bytes) / static_cast<double>(t.fragments.size());
  };
  state.counters["bytes_per_fragment"] = per_fragment(b.total());
  state.counters["position_bytes_per_fragment"] = per_fragment(b.positions);
  state.counters["attribute_bytes_per_fragment"] = per_fragment(b.attributes);
  state.counters["record_bytes_per_fragment"] = per_fragment(b.fragments);
  state.counters["node_bytes_per_fragment"] = per_fragment(b.nodes);
  state.counters["plane_bytes_per_fragment"] = per_fragment(b.planes);
}

// Median 1-thread build time per benchmark tail (scene, size, heuristic), for the 2-thread speedup.
std::map<std::string, double>& one_thread_medians() {
  static std::map<std::string, double> medians;
  return medians;
}

// How far the resident memory rose above where it started during one build, the finished tree
// included (resident_memory.h); measured on a build of its own, before the timed ones, once per
// benchmark (Google Benchmark calls a benchmark function again while it picks an iteration count).
std::optional<std::uint64_t> build_peak_bytes(const Scene& s, const std::string& h, const std::string& name) {
  static std::map<std::string, std::optional<std::uint64_t>> measured;
  if (const auto it = measured.find(name); it != measured.end()) return it->second;
  std::optional<std::uint64_t>& out = measured[name];
  const auto before = restart_peak();
  if (!before) return out;
  {
    auto splitter = make_splitter(h, {}, kSeed);
    const Tree t = build_tree(s.polygons, *splitter);
    benchmark::DoNotOptimize(t.nodes.data());
  }
  if (const auto peak = peak_resident()) out = *peak > *before ? *peak - *before : 0;
  return out;
}

void bm_build_vs_embree(benchmark::State& state, const Scene* s, std::string h, std::string tail, int threads) {
  omp_set_num_threads(threads);
  const auto peak = build_peak_bytes(*s, h, tail + "/threads:" + std::to_string(threads));
  const experiments::ReferenceBuild reference(s->polygons, threads);
  std::vector<double> times, embree_times, vs_embree, choosing, machinery, choose_seconds, machinery_seconds;
  BuildStats stats;  // the last run's; its counts are every run's
  for (auto _ : state) {
    const auto start = Clock::now();
    auto splitter = make_splitter(h, {}, kSeed);
    const Tree t = build_tree(s->polygons, *splitter);
    benchmark::DoNotOptimize(t.nodes.data());
    times.push_back(seconds_since(start));
    state.PauseTiming();
    const auto reference_start = Clock::now();
    reference.run();
    const double embree_time = seconds_since(reference_start);
    embree_times.push_back(embree_time);
    vs_embree.push_back(times.back() / embree_time);
    choosing.push_back(t.stats.choose_seconds / embree_time);
    machinery.push_back(t.stats.machinery_seconds / embree_time);
    choose_seconds.push_back(t.stats.choose_seconds);
    machinery_seconds.push_back(t.stats.machinery_seconds);
    stats = t.stats;
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s->polygons.size()));
  const double build = median(times);
  const double embree = median(embree_times);
  // On one thread the bill adds up to the build; on two its thread times include waits for a core
  // another process may hold, so there they are listed, not set against Embree.
  if (threads == 1) {
    state.counters["choose_vs_embree"] = median(choosing);
    state.counters["machinery_vs_embree"] = median(machinery);
    set_side_test_counters(state, stats, median(times), median(choose_seconds));
  } else {
    state.counters["choose_thread_seconds"] = median(choose_seconds);
    state.counters["machinery_thread_seconds"] = median(machinery_seconds);
  }
  omp_set_num_threads(1);
  const Tree& t = tree(*s, h, kSeed);
  set_tree_counters(state);
  state.counters["embree_bvh_seconds"] = embree;
  state.counters["build_vs_embree"] = median(vs_embree);
  // A fragment is visited once per level it passes on its way down: the sum of the stored
  // fragments' depths counts the visits (a split fragment's parts each count from the root).
  const double visits = state.counters["fragments"].value * state.counters["fragment_weighted_depth"].value;
  if (threads == 1 && visits > 0) state.counters["visit_nanoseconds"] = build / visits * 1e9;
  if (threads == 1) one_thread_medians()[tail] = build;
  else if (auto it = one_thread_medians().find(tail); it != one_thread_medians().end())
    state.counters["speedup"] = it->second / build;
  if (peak) state.counters["build_peak_vs_tree"] = static_cast<double>(*peak) / static_cast<double>(t.bytes());
  set_memory_counters(state, t);
}

void bm_traverse_vs_sort(benchmark::State& state, const Scene* s, std::string h) {
  const Tree& t = tree(*s, h, kSeed);
  const auto views = metric_views(t.bounds, kViews);
  EmbreePrimaryRays rays(s->polygons, views, kRayGrid);
  std::int64_t emitted = 0;
  std::vector<double> per_view, vs_rays;
  // Kept from view to view, as a renderer keeps its draw list (and as the sort's pairs are
  // allocated outside its timing).
  std::vector<std::uint32_t> draw_list;
  visibility_order(t, views.front().eye, Order::BackToFront, draw_list);  // its pages faulted in, untimed
  for (auto _ : state) {
    const auto start = Clock::now();
    for (const auto& v : views) emitted += visibility_order(t, v.eye, Order::BackToFront, draw_list).fragments_emitted;
    per_view.push_back(seconds_since(start) / static_cast<double>(views.size()));
    state.PauseTiming();
    vs_rays.push_back(per_view.back() / rays.seconds_per_view());
    state.ResumeTiming();
  }
  state.SetItemsProcessed(emitted);
  set_tree_counters(state);
  const double sort = depth_sort_seconds(t.fragments.size(), kReferenceRepeats);
  state.counters["sort_seconds"] = sort;
  state.counters["traverse_vs_sort"] = median(per_view) / sort;
  state.counters["traverse_vs_embree_rays"] = median(vs_rays);
}

void register_all(const Selection& sel) {
  for (const auto& name : sel.scenes)
    for (auto n : sel.sizes) {
      const Scene* s = &scene(name, scene_params(name, n));
      for (const auto& h : sel.heuristics) {
        const std::string tail = "/" + name + "/n:" + std::to_string(n) + "/" + h;
        for (int threads : {1, 2}) {
          auto* b = benchmark::RegisterBenchmark(("scaling/build" + tail + "/threads:" + std::to_string(threads)).c_str(),
                                                 bm_build_vs_embree, s, h, tail, threads);
          b->Unit(benchmark::kMillisecond)->UseRealTime();
          if (n >= kFixedBuildRunsN) b->Iterations(kBuildRuns);
        }
        auto* t = benchmark::RegisterBenchmark(("scaling/traverse" + tail).c_str(), bm_traverse_vs_sort, s, h);
        t->Unit(benchmark::kMillisecond)->UseRealTime();
        if (n >= kFixedTraversalRunsN) t->Iterations(kTraversalRuns);
      }
    }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel = bsp::bench::take_selection(argc, argv, {{"random-disjoint", "sphere-field"}, {}, {10000, 100000, 1000000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_scaling");
  } catch (const std::exception& e) {  // UsageError for a bad name or size
    std::cerr << "bspbench_bench_scaling: " << e.what() << "\n";
    return 2;
  }
}
