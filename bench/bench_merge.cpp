// bspbench_bench_merge: set operations by merging solid BSP trees [Naylor1990] beside CGAL's
// corefinement of the same meshes, in the same run:
//   merge/OP/PAIR/n:N/HEURISTIC   one iteration = build both operands' solid trees + merge +
//       reduce + the result's boundary as a welded mesh; items = input triangles of both operands;
//       counters: build_seconds, merge_seconds (merge and reduce), boundary_seconds (the boundary
//           extracted, welded and its T-junctions split: mesh out; with the closedness check's edge
//           report and volume, a few percent of it), the medians of the iterations;
//       peak_resident_bytes: the most the process held resident during an iteration (VmHWM after
//           a trim and restart before it; the operands and CGAL's copies of them included);
//       corefine_seconds: median of CGAL PMP::corefine_and_compute_OP on the same two meshes
//           (copies of both go in, since corefinement changes its inputs; the copies are timed);
//       below 10^5, the same merge with MergeOptions::prune_by_bounds on: pruned (subtrees passed
//       whole by their bounds), pruned_partition_nodes, pruned_merge_seconds and prune_speedup
//       (unpruned / pruned time, the two alternating on the same trees),
//       merge_vs_corefine (builds included), mesh_vs_corefine (builds and boundary included: mesh
//           in, mesh out, as corefinement) and merge_only_vs_corefine (merge and reduce only);
//       up to 10^4 triangles each, nef_seconds: median of CGAL's Nef polyhedra doing the same
//           (both conversions to Nef included; measured once per operands and operation), and
//           merge_vs_nef (builds included);
//       volume_difference: |IN cells' volume - corefinement's| / corefinement's;
//       result_nodes, result_depth (after reduce), nodes_before_reduce; partition_nodes,
//       shp_splits (merge cost); compactions (of the merge's work array); operand_nodes (both operands).
//   merge_kernel/OP/PAIR/n:N/HEURISTIC   the float and the exact kernel on the same operands in one
//       iteration (solid_build.h against exact_solid_tree.h, merge.h against exact_merge.h); one
//       thread; counters, the medians of the iterations: float_build_seconds, exact_build_seconds
//       (the strict build plus labels and sub-hyperplanes, each kernel's), exact_labels_seconds (the
//       sub-hyperplanes' part of it), float_merge_seconds, exact_merge_seconds (merge and reduce),
//       exact_merge_vs_float and exact_build_vs_float, the ratios of those medians; result_nodes of
//       each kernel.
// PAIR is sphere (the second sphere 0.9 the radius, its centre half a radius away; n triangles
// each) or a CGAL sample mesh with a copy of itself moved by 5% of its box (mesh:NAME), when the
// mesh cache has it.
//
// Which heuristics run where by default: chains (first and the autopartitions on a convex sphere)
// make building, merging and the boundary quadratic in time (compaction keeps merging's memory
// linear: solid/compaction.h), and naylor's build on a 10^4 sphere takes seconds; so 10^5 runs
// halving, octree and sah only, 10^6 (asked for with --bsp_sizes) octree and sah only, without the
// kernel comparison, and naylor stops at 10^4. A heuristic named with --bsp_heuristics runs on the
// spheres at every size asked for, once per operation where the default would skip it (a chain's
// 10^5 union takes minutes: docs/solids.md); the mesh pairs keep the defaults.
// Select with --bsp_heuristics and --bsp_sizes (bench_common.h), e.g.
//   build/bench/bspbench_bench_merge --bsp_sizes=10000 --bsp_heuristics=halving
//   build/bench/bspbench_bench_merge --bsp_sizes=1000000 --bsp_heuristics=octree
//   build/bench/bspbench_bench_merge --bsp_sizes=100000 --bsp_heuristics=crystal --benchmark_filter='^merge/union/sphere'
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <string_view>

#include "bench_common.h"
#include "catalog.h"
#include "mesh_scenes.h"
#include "metrics/statistics.h"
#include "resident_memory.h"
#include "solid/boundary.h"
#include "solid/cells.h"
#include "solid/exact_merge.h"
#include "solid/solid_build.h"
#include "split/registry.h"
#include "validate/exact_solid.h"

namespace bsp::bench {

namespace {

constexpr int kReferenceRepeats = 5;
constexpr std::uint64_t kLargeN = 100000;     // from here, halving, octree and sah only
constexpr std::uint64_t kHugeN = 1000000;     // from here, octree and sah only, and no kernel comparison
constexpr std::uint64_t kNaylorMaxN = 10000;
constexpr benchmark::IterationCount kSlowRuns = 3;  // iterations of runs that take seconds each
constexpr double kMeshOffset = 0.05;                // of the mesh's bounding box, per axis
constexpr std::uint64_t kNefMaxN = 10000;           // Nef polyhedra take about a second at 10^4
constexpr int kNefRepeats = 3;
constexpr int kPruneRepeats = 4;  // even: each merge first in half the rounds

using Clock = std::chrono::steady_clock;

struct Operands {
  std::string name;
  std::vector<Polygon> a, b;
  Box box;
  std::unique_ptr<ExactSolid> exact_a, exact_b;
};

Box bounds_of(const std::vector<Polygon>& polys) {
  Box b;
  for (const auto& p : polys)
    for (const auto& v : p.verts) b.add(v.p);
  return b;
}

Operands make_operands(std::string name, std::vector<Polygon> a, std::vector<Polygon> b) {
  Operands o{std::move(name), std::move(a), std::move(b), {}, nullptr, nullptr};
  o.box = solid_box(bounds_of(o.a), bounds_of(o.b));
  o.exact_a = std::make_unique<ExactSolid>(o.a);
  o.exact_b = std::make_unique<ExactSolid>(o.b);
  return o;
}

const Operands& sphere_pair(std::uint64_t n) {
  static std::map<std::uint64_t, Operands> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    const std::string count = std::to_string(n);
    it = cache.emplace(n, make_operands("sphere/" + count, scene("sphere", {{"n", count}}).polygons,
                                        scene("sphere", {{"n", count}, {"x", "0.5"}, {"scale", "0.9"}}).polygons))
             .first;
  }
  return it->second;
}

const Operands& mesh_pair(const std::string& name) {
  static std::map<std::string, Operands> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    std::vector<Polygon> a = scene(name, {}).polygons, b = a;
    const Vec3 d = bounds_of(a).size() * kMeshOffset;
    for (auto& p : b)
      for (auto& v : p.verts) v.p += d;
    it = cache.emplace(name, make_operands(name, std::move(a), std::move(b))).first;
  }
  return it->second;
}

// Median seconds of Nef polyhedra on the operands, measured once per operands and operation.
double nef_seconds(const Operands& o, SetOp op, double& volume) {
  static std::map<std::pair<std::string, SetOp>, std::pair<double, double>> measured;
  const auto key = std::make_pair(o.name, op);
  if (auto it = measured.find(key); it == measured.end()) {
    std::vector<double> times;
    double v = 0;
    for (int i = 0; i < kNefRepeats; ++i) {
      const NefResult r = nef_set_operation(o.a, o.b, op);
      times.push_back(r.seconds);
      v = r.volume;
    }
    measured[key] = {median(times), v};
  }
  volume = measured[key].second;
  return measured[key].first;
}

// The same merge with pruning by bounds (MergeOptions) on the same trees: what pruning changes.
// Below kLargeN only, where both run in seconds.
// Both merges alternate on the same trees, each first in every other round, so neither is favoured
// by warm caches.
void record_pruned(benchmark::State& state, const Operands& o, const std::string& h, SetOp op) {
  auto splitter = make_splitter(h, {}, kSeed);
  const SolidBuild a = build_solid(o.a, *splitter, o.box);
  const SolidBuild b = build_solid(o.b, *splitter, o.box);
  std::vector<double> times, pruned_times;  // times: unpruned, as merge/ runs
  MergeStats stats;
  for (int i = 0; i < kPruneRepeats; ++i) {
    for (const bool prune : {i % 2 == 0, i % 2 != 0}) {
      const auto start = Clock::now();
      const SolidTree r = merge(a.solid, b.solid, op, prune ? &stats : nullptr, MergeOptions{.prune_by_bounds = prune, .compaction = {}});
      (prune ? pruned_times : times).push_back(seconds_since(start));
    }
  }
  state.counters["pruned_merge_seconds"] = median(pruned_times);
  state.counters["prune_speedup"] = median(times) / median(pruned_times);
  state.counters["pruned"] = static_cast<double>(stats.pruned);
  state.counters["pruned_partition_nodes"] = static_cast<double>(stats.partition_nodes);
}

void bm_merge(benchmark::State& state, const Operands* o, std::string h, SetOp op, std::uint64_t n) {
  std::vector<double> builds, merges, boundaries;
  SolidTree result;
  MergeStats stats;
  std::uint64_t operand_nodes = 0, peak = 0;
  bool peak_known = true;
  for (auto _ : state) {
    result = SolidTree{};
    peak_known &= restart_peak().has_value();
    const auto start = Clock::now();
    auto splitter = make_splitter(h, {}, kSeed);
    const SolidBuild a = build_solid(o->a, *splitter, o->box);
    const SolidBuild b = build_solid(o->b, *splitter, o->box);
    builds.push_back(seconds_since(start));
    const auto merge_start = Clock::now();
    result = merge(a.solid, b.solid, op, &stats);
    merges.push_back(seconds_since(merge_start));
    const auto boundary_start = Clock::now();
    IndexedMesh mesh;
    check_boundary(solid_boundary(result), result.tol.plane_eps, &mesh);
    boundaries.push_back(seconds_since(boundary_start));
    operand_nodes = a.solid.nodes.size() + b.solid.nodes.size();
    const auto held = peak_resident();
    peak_known &= held.has_value();
    peak = std::max(peak, held.value_or(0));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(o->a.size() + o->b.size()));
  std::vector<double> corefines;
  double exact_volume = 0;
  for (int i = 0; i < kReferenceRepeats; ++i) {
    const auto start = Clock::now();
    exact_volume = corefine(*o->exact_a, *o->exact_b, op).volume;
    corefines.push_back(seconds_since(start));
  }
  const double build = median(builds), merge_only = median(merges), boundary = median(boundaries);
  const double reference = median(corefines);
  state.counters["build_seconds"] = build;
  state.counters["merge_seconds"] = merge_only;
  state.counters["boundary_seconds"] = boundary;
  state.counters["corefine_seconds"] = reference;
  state.counters["merge_vs_corefine"] = (build + merge_only) / reference;
  state.counters["mesh_vs_corefine"] = (build + merge_only + boundary) / reference;
  if (peak_known) state.counters["peak_resident_bytes"] = static_cast<double>(peak);
  state.counters["merge_only_vs_corefine"] = merge_only / reference;
  state.counters["volume_difference"] = std::abs(solid_volume(result) - exact_volume) / std::abs(exact_volume);
  state.counters["result_nodes"] = static_cast<double>(stats.after.nodes);
  state.counters["result_depth"] = static_cast<double>(stats.after.depth);
  state.counters["nodes_before_reduce"] = static_cast<double>(stats.before.nodes);
  state.counters["partition_nodes"] = static_cast<double>(stats.partition_nodes);
  state.counters["compactions"] = static_cast<double>(stats.compactions);
  state.counters["shp_splits"] = static_cast<double>(stats.shp_splits);
  state.counters["operand_nodes"] = static_cast<double>(operand_nodes);
  if (n < kLargeN) record_pruned(state, *o, h, op);
  if (std::max(o->a.size(), o->b.size()) <= kNefMaxN) {
    double nef_volume = 0;
    const double nef = nef_seconds(*o, op, nef_volume);
    state.counters["nef_seconds"] = nef;
    state.counters["merge_vs_nef"] = (build + merge_only) / nef;
    state.counters["nef_volume_difference"] = std::abs(nef_volume - exact_volume) / std::abs(exact_volume);
  }
}

void bm_kernel_merge(benchmark::State& state, const Operands* o, std::string h, SetOp op) {
  std::vector<double> float_builds, float_merges, exact_builds, exact_labels, exact_merges;
  MergeStats float_stats, exact_stats;
  for (auto _ : state) {
    auto splitter = make_splitter(h, {}, kSeed);
    auto start = Clock::now();
    const SolidBuild fa = build_solid(o->a, *splitter, o->box), fb = build_solid(o->b, *splitter, o->box);
    float_builds.push_back(seconds_since(start));
    merge(fa.solid, fb.solid, op, &float_stats);
    float_merges.push_back(float_stats.merge_seconds + float_stats.reduce_seconds);
    const auto space = ExactSolidSpace::for_box(o->box);
    start = Clock::now();
    const ExactSolidBuild ea = build_exact_solid(o->a, *splitter, *space), eb = build_exact_solid(o->b, *splitter, *space);
    exact_builds.push_back(seconds_since(start));
    exact_labels.push_back(ea.label_seconds + eb.label_seconds);
    merge(ea.solid, eb.solid, *space, op, &exact_stats);
    exact_merges.push_back(exact_stats.merge_seconds + exact_stats.reduce_seconds);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(o->a.size() + o->b.size()));
  const double fbuild = median(float_builds), fmerge = median(float_merges);
  const double ebuild = median(exact_builds), emerge = median(exact_merges);
  state.counters["float_build_seconds"] = fbuild;
  state.counters["exact_build_seconds"] = ebuild;
  state.counters["exact_labels_seconds"] = median(exact_labels);
  state.counters["float_merge_seconds"] = fmerge;
  state.counters["exact_merge_seconds"] = emerge;
  state.counters["exact_build_vs_float"] = ebuild / fbuild;
  state.counters["exact_merge_vs_float"] = emerge / fmerge;
  state.counters["float_result_nodes"] = static_cast<double>(float_stats.after.nodes);
  state.counters["exact_result_nodes"] = static_cast<double>(exact_stats.after.nodes);
}

bool runs_at(const std::string& h, std::uint64_t n) {
  if (n >= kHugeN) return h == "octree" || h == "sah";
  if (n >= kLargeN) return h == "halving" || h == "octree" || h == "sah";
  return h != "naylor" || n <= kNaylorMaxN;
}

void register_one(const std::string& pair, std::uint64_t n, const Operands* o, const std::string& h, SetOp op,
                  benchmark::IterationCount slow_runs) {
  const std::string name = "merge/" + std::string(set_op_name(op)) + "/" + pair + "/n:" + std::to_string(n) + "/" + h;
  auto* b = benchmark::RegisterBenchmark(name.c_str(), bm_merge, o, h, op, n);
  b->Unit(benchmark::kMillisecond)->UseRealTime();
  if (n >= 10000) b->Iterations(slow_runs);
  if (n >= kHugeN) return;
  const std::string kernel_name = "merge_kernel" + name.substr(name.find('/'));
  auto* k = benchmark::RegisterBenchmark(kernel_name.c_str(), bm_kernel_merge, o, h, op);
  k->Unit(benchmark::kMillisecond)->UseRealTime();
  if (n >= 10000) k->Iterations(slow_runs);
}

void register_all(const Selection& sel, bool heuristics_named) {
  const SetOp ops[] = {SetOp::Union, SetOp::Intersection, SetOp::Difference};
  for (auto n : sel.sizes)
    for (const auto& h : sel.heuristics) {
      const bool by_default = runs_at(h, n);
      if (by_default || heuristics_named)
        for (SetOp op : ops) register_one("sphere", n, &sphere_pair(n), h, op, by_default ? kSlowRuns : 1);
    }
  const std::vector<MeshEntry> meshes = available_meshes();
  for (const std::string mesh : {"mesh:elephant", "mesh:dino"}) {
    if (std::none_of(meshes.begin(), meshes.end(), [&](const auto& m) { return "mesh:" + m.name == mesh; })) continue;
    const Operands* o = &mesh_pair(mesh);
    for (const auto& h : sel.heuristics)
      if (runs_at(h, o->a.size()))
        for (SetOp op : ops) register_one(mesh, o->a.size(), o, h, op, kSlowRuns);
  }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    const bool heuristics_named = std::any_of(argv + 1, argv + argc, [](const char* a) {
      return std::string_view(a).starts_with("--bsp_heuristics");
    });
    const auto sel =
        bsp::bench::take_selection(argc, argv, {{}, {"first", "crystal", "halving", "naylor", "octree", "sah"}, {1000, 10000, 100000}});
    bsp::bench::register_all(sel, heuristics_named);
    return bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_merge");
  } catch (const std::exception& e) {
    std::cerr << "bspbench_bench_merge: " << e.what() << "\n";
    return 2;
  }
}
