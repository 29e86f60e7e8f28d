// bspbench_bench_csg: generated CSG programs (generators/csg_programs.h) evaluated mesh in to mesh
// out by merging solid trees, beside the peer engines on the same program in the same run:
//   csg/PROGRAM/k:K/HEURISTIC/KERNEL   one iteration = evaluate_program without its proof: every
//       leaf's solid tree, every merge, the boundary extracted and welded; items = the program's
//       binary operations; counters, medians of the iterations: build_seconds, merge_seconds,
//       boundary_seconds; result_faces, result_nodes; peak_resident_bytes (VmHWM during an
//       iteration, after a trim and restart before it);
//       cgal_seconds, manifold_seconds, openscad_seconds: each peer once on the same program
//       (experiments/csg/peers.h: CGAL's corefinement step by step in a child, Manifold under node,
//       OpenSCAD's render of the same file), -1 when a peer did not finish (missing, error, or past
//       --bsp_peer_timeout, default 600 s; the status is printed to stderr); vs_cgal, vs_manifold,
//       vs_openscad: our median over the peer's time (below 1: faster);
//       proved: 1 when one evaluation with its proof (points and exact volume against CGAL) held.
// PROGRAM is drilled-plate (a plate minus K holes) or sphere-union (K overlapping spheres); the
// plate drilled 1000 times is the iterated-CSG target, measured here and not in the suite.
//   build/bench/bspbench_bench_csg --bsp_sizes=1000 --benchmark_filter=drilled-plate
#include <iostream>
#include <map>

#include "bench_common.h"
#include "common/errors.h"
#include "csg_programs.h"
#include "experiments/csg/evaluate.h"
#include "experiments/csg/peers.h"
#include "experiments/csg/programs.h"
#include "metrics/statistics.h"
#include "resident_memory.h"
#include "split/registry.h"

namespace bsp::bench {

namespace {

double peer_timeout = experiments::kDefaultPeerTimeout;

struct Program {
  std::filesystem::path scratch;
  experiments::LoadedProgram loaded;
  std::map<std::string, experiments::PeerResult> peers;  // run once, on first use
};

std::map<std::string, std::unique_ptr<Program>>& programs() {
  static std::map<std::string, std::unique_ptr<Program>> cache;
  return cache;
}

Program& program(const std::string& name, std::uint64_t k) {
  auto& cache = programs();
  const std::string label = name + ":k=" + std::to_string(k);
  auto& p = cache[label];
  if (!p) {
    p = std::make_unique<Program>();
    p->scratch = experiments::scratch_folder("bench-" + name + "-" + std::to_string(k));
    p->loaded = experiments::load_program(experiments::parse_program_source(label), kSeed, p->scratch);
  }
  return *p;
}

// The peers' times, once per program, from the bspbench executable beside this binary.
void run_peers(Program& p) {
  if (!p.peers.empty()) return;
  const std::filesystem::path self = std::filesystem::path(BSPBENCH_EXE);
  for (const char* engine : {"cgal", "manifold", "openscad"}) {
    const auto r = experiments::run_peer(engine, p.loaded.file, p.loaded.postfix, p.scratch, {peer_timeout, self});
    if (r.status != "ok") std::cerr << "bspbench_bench_csg: " << engine << " on " << p.loaded.file.filename().string() << ": " << r.status << " " << r.note << "\n";
    p.peers[engine] = r;
  }
}

void bm_csg(benchmark::State& state, std::string name, std::uint64_t k, std::string heuristic, Kernel kernel) {
  Program& p = program(name, k);
  experiments::CsgSettings settings;
  settings.kernel = kernel;
  settings.prove = false;
  settings.check_inputs = false;  // checked once, with the proof, below
  std::vector<double> build, merge, boundary, total;
  std::uint64_t peak = 0, steps = 0, faces = 0, nodes = 0;
  for (auto _ : state) {
    restart_peak();
    const auto splitter = make_splitter(heuristic, {}, kSeed);
    const auto e = experiments::evaluate_program(p.loaded.program, p.loaded.postfix, *splitter, settings);
    peak = std::max(peak, peak_resident().value_or(0));
    build.push_back(e.build_seconds);
    merge.push_back(e.merge_seconds);
    boundary.push_back(e.boundary_seconds);
    total.push_back(e.seconds());
    steps = 0;
    for (const auto& s : e.steps) steps += s.merges;
    faces = e.mesh.face_count();
    nodes = e.result.nodes;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(steps));
  state.counters["build_seconds"] = median(build);
  state.counters["merge_seconds"] = median(merge);
  state.counters["boundary_seconds"] = median(boundary);
  state.counters["result_faces"] = static_cast<double>(faces);
  state.counters["result_nodes"] = static_cast<double>(nodes);
  state.counters["peak_resident_bytes"] = static_cast<double>(peak);
  settings.prove = true;
  settings.check_inputs = true;
  settings.check.points = 2000;
  const auto splitter = make_splitter(heuristic, {}, kSeed);
  state.counters["proved"] = experiments::evaluate_program(p.loaded.program, p.loaded.postfix, *splitter, settings).check.ok();
  run_peers(p);
  const double ours = median(total);
  for (const auto& [engine, r] : p.peers) {
    const bool ok = r.status == "ok";
    state.counters[engine + "_seconds"] = ok ? r.seconds : -1;
    state.counters["vs_" + engine] = ok ? ours / r.seconds : -1;
  }
}

}  // namespace

}  // namespace bsp::bench

int main(int argc, char** argv) {
  try {
    for (int i = 1; i < argc; ++i)
      if (std::string(argv[i]).rfind("--bsp_peer_timeout=", 0) == 0) {
        bsp::bench::peer_timeout = std::stod(argv[i] + 19);
        if (!(bsp::bench::peer_timeout > 0 && bsp::bench::peer_timeout <= 86400))
          throw bsp::UsageError("--bsp_peer_timeout takes seconds in (0, 86400]");
        for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
        --argc;
        break;
      }
    const auto sel = bsp::bench::take_selection(argc, argv, {{}, {"octree"}, {10, 100, 1000}});
    for (const auto& info : bsp::csg_programs())
      for (const auto k : sel.sizes)
        for (const auto& h : sel.heuristics)
          for (const auto kernel : {bsp::Kernel::Exact, bsp::Kernel::Float}) {
            const std::string name = "csg/" + std::string(info.name) + "/k:" + std::to_string(k) + "/" + h + "/" + bsp::kernel_name(kernel);
            benchmark::RegisterBenchmark(name.c_str(), bsp::bench::bm_csg, std::string(info.name), k, h, kernel)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime()
                ->Iterations(3);
          }
    const int rc = bsp::bench::run_benchmarks(argc, argv, "bspbench_bench_csg");
    for (const auto& [label, p] : bsp::bench::programs()) std::filesystem::remove_all(p->scratch);
    return rc;
  } catch (const std::exception& e) {
    std::cerr << "bspbench_bench_csg: " << e.what() << "\n";
    return 2;
  }
}
