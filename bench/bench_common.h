#pragma once
// Shared by the benchmark binaries (Google Benchmark 1.7.1, benchmarks registered at run time):
// selecting scenes, heuristics and sizes from the command line, generated scenes and built trees
// kept between benchmarks (so a traversal benchmark times traversal, not the build), tree metrics as
// counters, and the context every JSON output carries (git revision, scene hashes).
//
// Options, taken out of argv before Google Benchmark sees it:
//   --bsp_scenes=a,b  --bsp_heuristics=a,b  --bsp_sizes=1000,10000
//   --plugin=PATH.so (or --plugin PATH.so; repeatable): a plugin's heuristics, registered like
//   built-ins (docs/plugins.md) and named in the output's context
// Everything else goes to Google Benchmark (--benchmark_filter=REGEX selects by name,
// --benchmark_min_time=S, ...). Without --benchmark_out the JSON goes to
// results/runs/<binary>-<UTC time>.json in the source tree (git ignores results/runs/).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "common/params.h"
#include "scene/scene.h"
#include "tree/tree.h"

namespace bsp::bench {

struct Selection {
  std::vector<std::string> scenes;      // empty: every generator in the catalog
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<std::uint64_t> sizes;
};

// Removes the --bsp_* and --plugin options from argv and loads the plugins; what they do not set
// comes from `defaults`, and empty scene or heuristic lists become the whole catalog or registry.
// Throws UsageError on a bad value, InputError for a bad plugin.
Selection take_selection(int& argc, char** argv, Selection defaults);

// argv plus the default --benchmark_out (see above) when none is given; `binary` names the file.
std::vector<char*> with_default_output(int argc, char** argv, const std::string& binary, std::string& storage);

// Generates the scene once per (name, params) and records its content hash in the benchmark
// context as "scene_hash <name> <params>". Call while registering, before benchmarks run.
const Scene& scene(const std::string& name, const ParamAssignments& params);

// The tree of the last (scene, heuristic, seed) asked for, built once: benchmarks of one tree are
// registered one after another, so a single cached tree serves them all.
const Tree& tree(const Scene& scene, const std::string& heuristic, std::uint64_t seed);

// Every deterministic metric of measure_tree(default settings) of the tree last returned by tree()
// as a counter of `state`.
void set_tree_counters(benchmark::State& state);

// Seed and view count of every benchmark: the defaults of MetricsSettings.
inline constexpr std::uint64_t kSeed = 1;
inline constexpr std::uint32_t kViews = 8;

// build_tree of scene `s` with heuristic `h`; items = input polygons; counters = the tree's metrics.
void bm_build(benchmark::State& state, const Scene* s, std::string h);
// Full back-to-front traversal from the kViews metric views; items = fragments emitted.
void bm_traverse(benchmark::State& state, const Scene* s, std::string h);

// Seconds of wall time since `start` (steady clock), for the benchmarks' own in-run medians.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Adds the git revision to the context and runs the benchmarks; returns main's exit code: 2 for an
// unrecognized argument, 3 when a plugin's code threw (one line naming it on stderr).
int run_benchmarks(int argc, char** argv, const std::string& binary);

}  // namespace bsp::bench
