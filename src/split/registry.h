#pragma once
// Heuristics by name. Names are resolved only at the edges (CLI, benchmarks, tests, sweeps);
// everything inside takes a Splitter. Tests, benchmarks and sweeps iterate over heuristics(), so a
// heuristic added here is tested and measured without further wiring.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"
#include "split/splitter.h"

namespace bsp {

struct HeuristicInfo {
  std::string name;
  std::string summary;  // one line: what it optimises and where it comes from
  std::vector<ParamSpec> params;
  // True when every plane it picks is a fragment's plane (an autopartition).
  bool autopartition = true;
  // Builds a splitter from resolved parameters; `seed` feeds any randomness it has.
  std::function<std::unique_ptr<Splitter>(const ParamSet&, std::uint64_t seed)> make;
};

// Where a heuristic loaded at run time came from (experiments/plugin_loader.h): what joins the keys of
// the jobs that use it and the commands that repeat them.
struct PluginIdentity {
  std::string name;     // the plugin's own name
  std::string version;  // the plugin's own version
  std::string hash;     // 16 hex digits of the file's content (common/hash.h)
  std::string path;     // absolute, as loaded
  // "NAME VERSION HASH": the part that decides results (the path does not).
  std::string text() const { return name + " " + version + " " + hash; }
};

// The built-ins, then the heuristics plugins registered, in the order they were loaded. A deque:
// registering keeps references to the others valid.
const std::deque<HeuristicInfo>& heuristics();
// Adds a plugin's heuristic (experiments/plugin_loader.h, which checks the name first). Not while
// another thread looks heuristics up: the CLI registers at start-up, the Python module only when no
// call is running. Throws std::logic_error for a name already registered.
void register_heuristic(HeuristicInfo info, PluginIdentity from);
// The plugin that registered `name`, or null for a built-in.
const PluginIdentity* heuristic_plugin(std::string_view name);
// Throws UsageError naming the known heuristics.
const HeuristicInfo& find_heuristic(std::string_view name);
// Throws UsageError for an unknown heuristic, an unknown parameter or a bad value.
std::unique_ptr<Splitter> make_splitter(std::string_view name, const ParamAssignments& params, std::uint64_t seed);

// One declaration per heuristic file.
HeuristicInfo first_heuristic();
HeuristicInfo random_heuristic();
HeuristicInfo balanced_heuristic();
HeuristicInfo min_relation_heuristic();
HeuristicInfo weighted_heuristic();
HeuristicInfo quake_heuristic();
HeuristicInfo crystal_heuristic();
HeuristicInfo naylor_heuristic();
HeuristicInfo halving_heuristic();
HeuristicInfo octree_heuristic();
HeuristicInfo sah_heuristic();
HeuristicInfo zennode_heuristic();

}  // namespace bsp
