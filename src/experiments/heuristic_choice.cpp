#include "experiments/heuristic_choice.h"

#include <string_view>

#include "split/registry.h"

namespace bsp::experiments {

HeuristicLabel split_heuristic_label(const std::string& label) {
  const auto colon = label.find(':');
  HeuristicLabel v{label.substr(0, colon), {}};
  if (colon == std::string::npos) return v;
  std::string_view rest(label);
  rest.remove_prefix(colon + 1);
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    v.params.push_back(parse_assignment(rest.substr(0, comma)));
    rest.remove_prefix(comma == std::string_view::npos ? rest.size() : comma + 1);
  }
  return v;
}

HeuristicChoice HeuristicChoice::parse(const std::string& label) {
  HeuristicLabel split = split_heuristic_label(label);
  HeuristicChoice choice = of(split.name, std::move(split.params));
  choice.label = label;
  return choice;
}

HeuristicChoice HeuristicChoice::of(const std::string& name, ParamAssignments params) {
  const HeuristicInfo& h = find_heuristic(name);
  ParamSet resolved = ParamSet::resolve(h.params, params, "heuristic " + h.name);
  std::string label = h.name;
  for (std::size_t i = 0; i < params.size(); ++i) label += (i == 0 ? ":" : ",") + params[i].first + "=" + params[i].second;
  return {std::move(label), h.name, std::move(params), std::move(resolved)};
}

std::vector<HeuristicChoice> choices_or_all(const std::vector<std::string>& labels) {
  std::vector<HeuristicChoice> out;
  if (labels.empty())
    for (const auto& h : heuristics()) out.push_back(HeuristicChoice::parse(h.name));
  for (const auto& label : labels) out.push_back(HeuristicChoice::parse(label));
  return out;
}

std::string HeuristicChoice::arguments() const {
  std::string out = " --heuristic " + name;
  for (const auto& [k, value] : params) out += " --param " + k + "=" + value;
  return out;
}

std::unique_ptr<Splitter> HeuristicChoice::splitter(std::uint64_t seed) const {
  return find_heuristic(name).make(resolved, seed);
}

}  // namespace bsp::experiments
