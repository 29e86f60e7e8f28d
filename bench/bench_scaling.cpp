// bspbench_bench_scaling: build and full traversal on random-triangles at
// N = 10^3, 10^4, 10^5, tree metrics as counters:
//   scaling/build/n:N/HEURISTIC     items = input triangles
//   scaling/traverse/n:N/HEURISTIC  back-to-front from the 8 metric views; items = fragments emitted
//
// The triangles' `size` shrinks as 0.1 * (1000 / N)^(1/3), the generator's default at N = 10^3,
// so each triangle overlaps about as many others at every N and the growth measured is the
// heuristic's, not the clutter's. (At the fixed default size, 10^5 triangles split into ~15 million
// fragments: ~7 GB and minutes per build.)
//
// Default heuristics: first, random and crystal, whose builds stay near n log n; the exhaustive
// scorers take hours at 10^5 — pick them with --bsp_heuristics (and smaller --bsp_sizes), e.g.
//   build/bench/bspbench_bench_scaling --bsp_heuristics=quake,naylor --bsp_sizes=1000,10000
#include <cmath>
#include <iostream>

#include "bench_common.h"
#include "metrics/traversal_cost.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"

namespace bsp::bench {

namespace {

constexpr double kDefaultSize = 0.1;   // random-triangles' default `size`
constexpr double kDefaultN = 1000;     // the N at which it applies unchanged

std::string size_for(std::uint64_t n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", kDefaultSize * std::cbrt(kDefaultN / static_cast<double>(n)));
  return buf;
}

void register_all(const Selection& sel) {
  for (auto n : sel.sizes) {
    const Scene* s = &scene("random-triangles",
                            {{"n", std::to_string(n)}, {"seed", std::to_string(kSeed)}, {"size", size_for(n)}});
    for (const auto& h : sel.heuristics) {
      const std::string tail = "/n:" + std::to_string(n) + "/" + h;
      benchmark::RegisterBenchmark(("scaling/build" + tail).c_str(), bm_build, s, h)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark(("scaling/traverse" + tail).c_str(), bm_traverse, s, h)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel =
        bsp::bench::take_selection(argc, argv, {{"random-triangles"}, {"first", "random", "crystal"}, {1000, 10000, 100000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_scaling");
  } catch (const std::exception& e) {  // UsageError for a bad name or size
    std::cerr << "bspbench_bench_scaling: " << e.what() << "\n";
    return 2;
  }
}
