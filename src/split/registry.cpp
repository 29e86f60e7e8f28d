#include "split/registry.h"

#include "common/errors.h"

namespace bsp {

const std::vector<HeuristicInfo>& heuristics() {
  static const std::vector<HeuristicInfo> all = {
      first_heuristic(),
      random_heuristic(),
      balanced_heuristic(),
      min_relation_heuristic(),
      weighted_heuristic(),
      quake_heuristic(),
      crystal_heuristic(),
      naylor_heuristic(),
      halving_heuristic(),
      octree_heuristic(),
      sah_heuristic(),
      zennode_heuristic(),
  };
  return all;
}

const HeuristicInfo& find_heuristic(std::string_view name) {
  for (const auto& h : heuristics())
    if (h.name == name) return h;
  std::string known;
  for (const auto& h : heuristics()) known += (known.empty() ? "" : ", ") + h.name;
  throw UsageError("unknown heuristic '" + std::string(name) + "' (known: " + known + ")");
}

std::unique_ptr<Splitter> make_splitter(std::string_view name, const ParamAssignments& params, std::uint64_t seed) {
  const HeuristicInfo& info = find_heuristic(name);
  return info.make(ParamSet::resolve(info.params, params, "heuristic " + info.name), seed);
}

}  // namespace bsp
