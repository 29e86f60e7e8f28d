#include "split/registry.h"

#include <stdexcept>
#include <utility>

#include "common/errors.h"

namespace bsp {

namespace {

// The registry: built-ins first. Plugins add to it at start-up only (register_heuristic), so
// lookups during a run read a table no one writes.
struct Registry {
  std::deque<HeuristicInfo> all = {
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
  std::vector<std::pair<std::string, PluginIdentity>> plugins;  // by heuristic name
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

const std::deque<HeuristicInfo>& heuristics() { return registry().all; }

void register_heuristic(HeuristicInfo info, PluginIdentity from) {
  Registry& r = registry();
  for (const auto& h : r.all)
    if (h.name == info.name) throw std::logic_error("register_heuristic: '" + info.name + "' is registered already");
  r.plugins.emplace_back(info.name, std::move(from));
  r.all.push_back(std::move(info));
}

const PluginIdentity* heuristic_plugin(std::string_view name) {
  for (const auto& [heuristic, plugin] : registry().plugins)
    if (heuristic == name) return &plugin;
  return nullptr;
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
