// bspbench_bench_occlusion: occlusion culling by beam tracing (src/cull) beside frustum culling and
// Embree ray casting of the same views, in the same run:
//   occlude/SCENE/n:N/HEURISTIC   one iteration = culling each of 8 metric views (metric_views) once;
//       items = views; counters, per view:
//       occlude_seconds: median over the iterations; frustum_seconds: the culled back-to-front
//           traversal of the same views (traverse_culled.h), what occlusion culling adds work to;
//       occlude_vs_frustum: their ratio; embree_rays_seconds: Embree casting a 256 x 256 primary-ray
//           image of the view (references.h), the ray-casting way to the visible set;
//           occlude_vs_embree: the ratio; emitted, frustum_culled: fragments each emits (means);
//           beam_nodes: the beam tree's size at the end (mean).
// Select scenes, sizes and heuristics with --bsp_scenes, --bsp_sizes and --bsp_heuristics.
#include <iostream>
#include <vector>

#include "bench_common.h"
#include "catalog.h"
#include "cull/occlusion.h"
#include "metrics/statistics.h"
#include "metrics/traversal_cost.h"
#include "references.h"
#include "split/registry.h"
#include "tree/build.h"

namespace bsp::bench {

namespace {

constexpr std::uint32_t kViews = 8;
constexpr int kEmbreeGrid = 256;
constexpr int kReferenceRepeats = 5;

double per_view(double seconds) { return seconds / kViews; }

void bm_occlude(benchmark::State& state, std::string scene_name, std::uint64_t n, std::string heuristic) {
  const Scene scene = make_scene(scene_name, {{"n", std::to_string(n)}, {"seed", std::to_string(kSeed)}});
  auto splitter = make_splitter(heuristic, {}, kSeed);
  const Tree tree = build_tree(scene.polygons, *splitter);
  const Occluder occluder(tree);
  const std::vector<Frustum> views = metric_views(tree.bounds, kViews);
  std::vector<double> times;
  double emitted = 0, beam = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    for (const Frustum& v : views) benchmark::DoNotOptimize(occluder.visible(v).data());
    times.push_back(per_view(seconds_since(start)));
  }
  double frustum_emitted = 0;
  std::vector<double> frustum_times;
  for (int r = 0; r < kReferenceRepeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    for (const Frustum& v : views) frustum_emitted += static_cast<double>(traverse_culled(tree, v, [](std::uint32_t) {}).fragments_emitted);
    frustum_times.push_back(per_view(seconds_since(start)));
  }
  for (const Frustum& v : views) {
    OcclusionCounters c;
    emitted += static_cast<double>(occluder.visible(v, &c).size());
    beam += static_cast<double>(c.beam_nodes);
  }
  state.SetItemsProcessed(state.iterations() * kViews);
  const double occlude = median(times), frustum = median(frustum_times);
  const double embree = embree_primary_rays_seconds(scene.polygons, views, kEmbreeGrid, kReferenceRepeats);
  state.counters["occlude_seconds"] = occlude;
  state.counters["frustum_seconds"] = frustum;
  state.counters["occlude_vs_frustum"] = occlude / frustum;
  state.counters["embree_rays_seconds"] = embree;
  state.counters["occlude_vs_embree"] = occlude / embree;
  state.counters["emitted"] = emitted / kViews;
  state.counters["frustum_culled"] = frustum_emitted / (kViews * kReferenceRepeats);
  state.counters["beam_nodes"] = beam / kViews;
}

void register_all(const Selection& sel) {
  for (const auto& scene : sel.scenes)
    for (auto n : sel.sizes)
      for (const auto& h : sel.heuristics) {
        const std::string name = "occlude/" + scene + "/n:" + std::to_string(n) + "/" + h;
        benchmark::RegisterBenchmark(name.c_str(), bm_occlude, scene, n, h)->Unit(benchmark::kMillisecond)->UseRealTime();
      }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const auto sel = bsp::bench::take_selection(argc, argv,
                                                {{"architecture", "city", "terrain"}, {"crystal"}, {1000, 10000}});
    bsp::bench::register_all(sel);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_occlusion");
  } catch (const std::exception& e) {
    std::cerr << "bspbench_bench_occlusion: " << e.what() << "\n";
    return 2;
  }
}
