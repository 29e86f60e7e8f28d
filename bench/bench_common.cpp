#include "bench_common.h"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "catalog.h"
#include "common/errors.h"
#include "common/revision.h"
#include "experiments/draw/draw.h"
#include "experiments/plugin_loader.h"
#include "metrics/traversal_cost.h"
#include "metrics/tree_metrics.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"

namespace bsp::bench {

namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<std::uint64_t> parse_sizes(const std::string& text) {
  std::vector<std::uint64_t> out;
  for (const auto& item : split_list(text)) {
    std::size_t used = 0;
    const auto v = std::stoull(item, &used);
    if (used != item.size() || v == 0) throw UsageError("--bsp_sizes wants positive integers, not '" + item + "'");
    out.push_back(v);
  }
  return out;
}

std::string utc_stamp() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%dT%H%M%SZ", &tm);
  return buf;
}

struct CachedTree {
  std::string key;
  std::unique_ptr<Tree> tree;
  nlohmann::json metrics;  // deterministic fields of to_json(measure_tree(tree, {}))
};

CachedTree& cached_tree() {
  static CachedTree cache;
  return cache;
}

// Loads a plugin and names it in the output's context, as a sweep's environment does.
void load_plugin(const std::string& path) {
  const PluginIdentity& p = experiments::load_plugin(path);
  benchmark::AddCustomContext("plugin " + p.name, p.version + " " + p.hash + " " + p.path);
}

}  // namespace

Selection take_selection(int& argc, char** argv, Selection defaults) {
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* flag) { return arg.substr(std::string(flag).size()); };
    if (arg.rfind("--plugin=", 0) == 0) load_plugin(value("--plugin="));
    else if (arg == "--plugin" && i + 1 < argc) load_plugin(argv[++i]);
    else if (arg == "--plugin") throw UsageError("--plugin needs the path of a plugin (a .so)");
    else if (arg.rfind("--bsp_scenes=", 0) == 0) defaults.scenes = split_list(value("--bsp_scenes="));
    else if (arg.rfind("--bsp_heuristics=", 0) == 0) defaults.heuristics = split_list(value("--bsp_heuristics="));
    else if (arg.rfind("--bsp_sizes=", 0) == 0) defaults.sizes = parse_sizes(value("--bsp_sizes="));
    else argv[kept++] = argv[i];
  }
  argc = kept;
  if (defaults.scenes.empty())
    for (const auto& g : generators())
      if (!g.segments) defaults.scenes.push_back(g.name);
  if (defaults.heuristics.empty())
    for (const auto& h : heuristics()) defaults.heuristics.push_back(h.name);
  for (const auto& h : defaults.heuristics) find_heuristic(h);
  return defaults;
}

std::vector<char*> with_default_output(int argc, char** argv, const std::string& binary, std::string& storage) {
  std::vector<char*> args(argv, argv + argc);
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]).rfind("--benchmark_out=", 0) == 0) return args;
  const auto dir = std::filesystem::path(BSPBENCH_SOURCE_DIR) / "results" / "runs";
  std::filesystem::create_directories(dir);
  storage = "--benchmark_out=" + (dir / (binary + "-" + utc_stamp() + ".json")).string();
  args.push_back(storage.data());
  static std::string format = "--benchmark_out_format=json";
  args.push_back(format.data());
  return args;
}

const Scene& scene(const std::string& name, const ParamAssignments& params) {
  static std::map<std::string, std::unique_ptr<Scene>> scenes;
  std::string key = name;
  for (const auto& [k, v] : params) key += " " + k + "=" + v;
  auto& slot = scenes[key];
  if (!slot) {
    slot = std::make_unique<Scene>(make_scene(name, params));
    benchmark::AddCustomContext("scene_hash " + key, content_hash(*slot));
  }
  return *slot;
}

const Tree& tree(const Scene& scene, const std::string& heuristic, std::uint64_t seed) {
  CachedTree& c = cached_tree();
  const std::string key = content_hash(scene) + " " + heuristic + " " + std::to_string(seed);
  if (c.key != key) {
    c.tree.reset();  // free the previous tree before building the next
    auto splitter = make_splitter(heuristic, {}, seed);
    c.tree = std::make_unique<Tree>(build_tree(scene.polygons, *splitter));
    c.metrics = to_json(measure_tree(*c.tree, MetricsSettings{}));
    nlohmann::json timings;
    experiments::split_timings(c.metrics, timings, "", experiments::draw_timing_fields());
    c.key = key;
  }
  return *c.tree;
}

void set_tree_counters(benchmark::State& state) {
  const CachedTree& c = cached_tree();
  for (const auto& [k, v] : c.metrics.items())
    if (v.is_number()) state.counters[k] = benchmark::Counter(v.get<double>());
}

int run_benchmarks(int argc, char** argv, const std::string& binary) {
  benchmark::AddCustomContext("git_revision", bsp::git_revision());
  std::string storage;
  std::vector<char*> args = with_default_output(argc, argv, binary, storage);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 2;
  try {
    benchmark::RunSpecifiedBenchmarks();
  } catch (const PluginError& e) {  // thrown by a build after a plugin's splitter failed
    std::cerr << binary << ": " << e.what() << "\n";
    return 3;
  }
  benchmark::Shutdown();
  return 0;
}

void bm_build(benchmark::State& state, const Scene* s, std::string h) {
  for (auto _ : state) {
    auto splitter = make_splitter(h, {}, kSeed);
    const Tree t = build_tree(s->polygons, *splitter);
    benchmark::DoNotOptimize(t.nodes.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(s->polygons.size()));
  tree(*s, h, kSeed);
  set_tree_counters(state);
}

void bm_traverse(benchmark::State& state, const Scene* s, std::string h) {
  const Tree& t = tree(*s, h, kSeed);
  const auto views = metric_views(t.bounds, kViews);
  std::int64_t emitted = 0;
  std::vector<std::uint32_t> draw_list;  // kept from view to view, as a renderer keeps its own
  for (auto _ : state)
    for (const auto& v : views) emitted += visibility_order(t, v.eye, Order::BackToFront, draw_list).fragments_emitted;
  state.SetItemsProcessed(emitted);
  set_tree_counters(state);
}

}  // namespace bsp::bench
