#include "experiments/heuristic_choice.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "common/errors.h"
#include "search/tree_search.h"
#include "split/registry.h"
#include "tree/build.h"

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

const std::vector<ParamSpec>& params_of(const std::string& name) {
  if (const SearchInfo* s = find_search(name)) return s->params;
  for (const auto& h : heuristics())
    if (h.name == name) return h.params;
  std::string known;
  for (const auto& h : heuristics()) known += (known.empty() ? "" : ", ") + h.name;
  for (const auto& s : searches()) known += ", " + s.name;
  throw UsageError("unknown heuristic '" + name + "' (known: " + known + ")");
}

HeuristicChoice HeuristicChoice::of(const std::string& name, ParamAssignments params) {
  const bool search = find_search(name) != nullptr;
  ParamSet resolved = ParamSet::resolve(params_of(name), params, (search ? "search " : "heuristic ") + name);
  if (search) find_search(name)->check(resolved);
  std::string label = name;
  for (std::size_t i = 0; i < params.size(); ++i) label += (i == 0 ? ":" : ",") + params[i].first + "=" + params[i].second;
  return {std::move(label), name, search, std::move(params), std::move(resolved)};
}

std::vector<HeuristicChoice> choices_or_all(const std::vector<std::string>& labels) {
  std::vector<HeuristicChoice> out;
  if (labels.empty())
    for (const auto& h : heuristics()) out.push_back(HeuristicChoice::parse(h.name));
  for (const auto& label : labels) out.push_back(HeuristicChoice::parse(label));
  return out;
}

std::vector<HeuristicChoice> per_node_choices_or_all(const std::vector<std::string>& labels, const std::string& what) {
  std::vector<HeuristicChoice> out = choices_or_all(labels);
  for (const HeuristicChoice& h : out) h.require_per_node(what);
  return out;
}

std::unique_ptr<Splitter> per_node_splitter(const std::string& name, const ParamAssignments& params, std::uint64_t seed) {
  return HeuristicChoice::of(name, params).splitter(seed);
}

void add_plugin_identity(Hasher& key, const std::string& name) {
  if (const PluginIdentity* p = heuristic_plugin(name)) key.add_string("plugin " + p->text());
}

namespace {

// `word` as one word of a shell command: as it is when it holds only characters no shell treats
// specially, else in single quotes.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](unsigned char c) {
    return std::isalnum(c) || std::string_view("_./+-=:,@%").find(static_cast<char>(c)) != std::string_view::npos;
  });
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string plugin_arguments(const std::string& name) {
  const PluginIdentity* p = heuristic_plugin(name);
  return p ? " --plugin " + shell_word(p->path) : std::string();
}

std::string HeuristicChoice::arguments() const {
  std::string out = plugin_arguments(name) + " --heuristic " + name;
  for (const auto& [k, value] : params) out += " --param " + k + "=" + value;
  return out;
}

void HeuristicChoice::require_per_node(const std::string& what) const {
  if (search)
    throw UsageError(name + " is a searching builder, which builds whole trees; " + what +
                     " builds per node and needs a heuristic (bspbench heuristics lists both)");
}

std::unique_ptr<Splitter> HeuristicChoice::splitter(std::uint64_t seed) const {
  require_per_node("this command or experiment");
  return find_heuristic(name).make(resolved, seed);
}

bool HeuristicChoice::autopartition() const {
  return find_heuristic(search ? resolved.choice("base") : name).autopartition;
}

Tree HeuristicChoice::build(std::span<const Polygon> input, const BuildOptions& options, std::uint64_t seed) const {
  if (search) return find_search(name)->build(input, options, resolved, seed);
  return build_tree(input, *splitter(seed), options);
}

}  // namespace bsp::experiments
