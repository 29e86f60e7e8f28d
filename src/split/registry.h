#pragma once
// Heuristics by name. Names are resolved only at the edges (CLI, benchmarks, tests, sweeps);
// everything inside takes a Splitter. Tests, benchmarks and sweeps iterate over heuristics(), so a
// heuristic added here is tested and measured without further wiring.
#include <cstdint>
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

const std::vector<HeuristicInfo>& heuristics();
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
