// Notation: a trial is one full build (decisions + the base below them) with its cost and the
// record of its top nodes; X is the node a step decides; D the decisions made so far.
#include "search/tree_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "common/rng.h"
#include "search/decisions.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/depth.h"

namespace bsp {

namespace {

enum class Objective { Fragments, Depth };

// Lexicographic: the objective's measure, then the other.
struct Cost {
  std::int64_t first = 0, second = 0;
  auto operator<=>(const Cost&) const = default;
};

Objective objective_of(const ParamSet& p) {
  return p.choice("objective") == "depth" ? Objective::Depth : Objective::Fragments;
}

Cost cost_of(const Tree& t, Objective o) {
  const auto fragments = static_cast<std::int64_t>(t.fragments.size());
  const std::int64_t depth = max_depth(t);
  return o == Objective::Fragments ? Cost{fragments, depth} : Cost{depth, fragments};
}

// What every build of a search spent, summed: the kept tree is billed for the whole search.
struct SearchBill {
  double choose_seconds = 0, machinery_seconds = 0;
  std::uint64_t side_tests = 0, choose_side_tests = 0;

  void add(const BuildStats& s) {
    choose_seconds += s.choose_seconds;
    machinery_seconds += s.machinery_seconds;
    side_tests += s.side_tests;
    choose_side_tests += s.choose_side_tests;
  }
  void charge(BuildStats& s) const {
    s.choose_seconds = choose_seconds;
    s.machinery_seconds = machinery_seconds;
    s.side_tests = side_tests;
    s.choose_side_tests = choose_side_tests;
  }
};

struct Trial {
  Tree tree;
  std::shared_ptr<const Decisions> decisions;
  std::map<std::uint64_t, RecordedNode> recorded;
  Cost cost;
};

using OpenNode = std::pair<std::uint64_t, const RecordedNode*>;

// The shallowest node of depth `levels` or less that the trial left to the base and that has an
// alternative, ties by key; none when every such node is decided. (The record can go deeper: the
// lookahead's children.)
std::optional<OpenNode> next_open(const Trial& t, std::uint32_t levels) {
  std::optional<OpenNode> best;
  for (const auto& [key, node] : t.recorded) {
    if (node.depth > levels || node.options.size() < 2 || t.decisions->contains(key)) continue;
    if (!best || node.depth < best->second->depth) best = OpenNode{key, &node};
  }
  return best;
}

// What every search shares: the input, the base, and full builds that count themselves.
class Builds {
 public:
  Builds(std::span<const Polygon> input, const BuildOptions& options, const ParamSet& p, std::uint64_t seed,
         RecordSettings record, SearchBill& bill)
      : input_(input), options_(options), base_(p.choice("base")), seed_(seed), record_(record), bill_(bill),
        objective_(objective_of(p)) {}

  Trial build(Decisions d) {
    auto decisions = std::make_shared<const Decisions>(std::move(d));
    auto recorder = std::make_shared<Recorder>(record_);
    DecisionSplitter splitter(decisions, make_splitter(base_, {}, seed_), recorder);
    Tree tree = build_tree(input_, splitter, options_);
    bill_.add(tree.stats);
    const Cost cost = cost_of(tree, objective_);
    return {std::move(tree), std::move(decisions), recorder->nodes(), cost};
  }

  // The trial `from` with `key` decided as its option `option` > 0: a new build.
  Trial extend(const Trial& from, std::uint64_t key, std::size_t option) {
    Decisions d = *from.decisions;
    d[key] = from.recorded.at(key).options[option];
    return build(std::move(d));
  }

  // The trial with `key` decided as what its base chose there: the same tree, no build.
  static Trial keep(Trial&& from, std::uint64_t key) {
    Decisions d = *from.decisions;
    d[key] = from.recorded.at(key).options.front();
    from.decisions = std::make_shared<const Decisions>(std::move(d));
    return std::move(from);
  }

 private:
  std::span<const Polygon> input_;
  const BuildOptions& options_;
  std::string base_;
  std::uint64_t seed_;
  RecordSettings record_;
  SearchBill& bill_;
  Objective objective_;
};

RecordSettings record_settings(const ParamSet& p, std::uint32_t extra_depth) {
  return {static_cast<std::uint32_t>(p.integer("levels")) + extra_depth, static_cast<std::uint32_t>(p.integer("width")),
          RecordSettings{}.pool};
}

// The best a child of X can do with one other option than its base's: how much its cost drops.
std::int64_t child_gain(Builds& builds, const Trial& t, std::uint64_t child) {
  const auto it = t.recorded.find(child);
  if (it == t.recorded.end()) return 0;
  std::int64_t gain = 0;
  for (std::size_t q = 1; q < it->second.options.size(); ++q) {
    Decisions d = *t.decisions;
    d[child] = it->second.options[q];
    gain = std::max(gain, t.cost.first - builds.build(std::move(d)).cost.first);
  }
  return gain;
}

Tree lookahead(std::span<const Polygon> input, const BuildOptions& options, const ParamSet& p, std::uint64_t seed,
               SearchBill& bill) {
  const auto depth = static_cast<std::uint32_t>(p.integer("depth"));
  Builds builds(input, options, p, seed, record_settings(p, depth), bill);
  const auto levels = static_cast<std::uint32_t>(p.integer("levels"));
  Trial best = builds.build({});
  while (const auto open = next_open(best, levels)) {
    const auto [key, node] = *open;
    std::optional<Trial> chosen;
    std::pair<std::int64_t, Cost> chosen_score;
    for (std::size_t i = node->options.size(); i-- > 0;) {
      Trial t = i > 0 ? builds.extend(best, key, i) : Builds::keep(std::move(best), key);
      std::int64_t score = t.cost.first;
      if (depth > 0)
        for (const bool front : {true, false}) score -= child_gain(builds, t, SplitContext::child_key(key, front));
      // Ties go to the lower option (the base's choice first): options are tried last to first.
      const std::pair<std::int64_t, Cost> s{score, t.cost};
      if (!chosen || !(chosen_score < s)) {
        chosen_score = s;
        chosen = std::move(t);
      }
    }
    best = std::move(*chosen);
  }
  return std::move(best.tree);
}

Tree beam(std::span<const Polygon> input, const BuildOptions& options, const ParamSet& p, std::uint64_t seed,
          SearchBill& bill) {
  const auto keep = static_cast<std::size_t>(p.integer("beam"));
  Builds builds(input, options, p, seed, record_settings(p, 0), bill);
  const auto levels = static_cast<std::uint32_t>(p.integer("levels"));
  std::vector<Trial> states;
  states.push_back(builds.build({}));
  for (bool expanded = true; expanded;) {
    expanded = false;
    std::vector<Trial> next;
    for (Trial& s : states) {
      const auto open = next_open(s, levels);
      if (!open) {
        next.push_back(std::move(s));
        continue;
      }
      expanded = true;
      const auto [key, node] = *open;
      std::vector<Trial> children;
      for (std::size_t i = 1; i < node->options.size(); ++i) children.push_back(builds.extend(s, key, i));
      next.push_back(Builds::keep(std::move(s), key));
      for (Trial& c : children) next.push_back(std::move(c));
    }
    // Stable: among equal costs the earlier state (its parent's rank, then its option) stays.
    std::stable_sort(next.begin(), next.end(), [](const Trial& a, const Trial& b) { return a.cost < b.cost; });
    if (next.size() > keep) next.erase(next.begin() + static_cast<std::ptrdiff_t>(keep), next.end());
    states = std::move(next);
  }
  return std::move(states.front().tree);
}

// The value restart i of n gives the varied parameter: evenly spaced from `from` to `to`,
// geometrically when both are positive (a penalty or a threshold matters by its order).
std::string varied_value(const ParamSet& p, std::int64_t i, std::int64_t n, bool integer) {
  const double from = p.real("from"), to = p.real("to");
  const double t = n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
  const double v = from > 0 && to > 0 ? from * std::pow(to / from, t) : from + (to - from) * t;
  std::ostringstream text;
  text.precision(17);
  if (integer) text << std::llround(v);
  else text << v;
  return text.str();
}

// The base's parameter restarts varies; null for the seed. Throws UsageError when the base has no
// such parameter.
const ParamSpec* varied_spec(const ParamSet& p) {
  const std::string& vary = p.choice("vary");
  if (vary == "seed") return nullptr;
  const HeuristicInfo& info = find_heuristic(p.choice("base"));
  for (const ParamSpec& s : info.params)
    if (s.name == vary) return &s;
  throw UsageError("restarts: heuristic " + info.name + " has no parameter " + vary + " to vary");
}

Tree restarts(std::span<const Polygon> input, const BuildOptions& options, const ParamSet& p, std::uint64_t seed,
              SearchBill& bill) {
  const std::string& base = p.choice("base");
  const std::string& vary = p.choice("vary");
  const ParamSpec* spec = varied_spec(p);
  const Objective objective = objective_of(p);
  const std::int64_t n = p.integer("n");
  std::optional<Tree> best;
  Cost best_cost;
  for (std::int64_t i = 0; i < n; ++i) {
    ParamAssignments given;
    std::uint64_t restart_seed = seed;
    if (vary == "seed") restart_seed = stream_seed(seed, static_cast<std::uint64_t>(i));
    else given.push_back({vary, varied_value(p, i, n, spec->kind == ParamSpec::Kind::Integer)});
    const auto splitter = make_splitter(base, given, restart_seed);
    Tree t = build_tree(input, *splitter, options);
    bill.add(t.stats);
    const Cost c = cost_of(t, objective);
    if (!best || c < best_cost) {
      best_cost = c;
      best = std::move(t);
    }
  }
  return std::move(*best);
}

using SearchFn = Tree (*)(std::span<const Polygon>, const BuildOptions&, const ParamSet&, std::uint64_t, SearchBill&);

// The search as registered: the tree it keeps, billed with the whole search (the time and the side
// tests of every build it made), not with the one build that made the tree.
template <SearchFn search>
Tree billed(std::span<const Polygon> input, const BuildOptions& options, const ParamSet& p, std::uint64_t seed) {
  const auto start = std::chrono::steady_clock::now();
  SearchBill bill;
  Tree tree = search(input, options, p, seed, bill);
  tree.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bill.charge(tree.stats);
  return tree;
}

// The bases a search can take, `weighted` first: a choice's first is its default, and weighted's
// sampled candidates keep the many builds of a search near n log n each.
std::vector<std::string> heuristic_names() {
  std::vector<std::string> names{"weighted"};
  for (const auto& h : heuristics())
    if (h.name != names.front()) names.push_back(h.name);
  return names;
}

// Every numeric parameter of any heuristic, after "seed": what restarts can vary.
std::vector<std::string> variable_names() {
  std::vector<std::string> names{"seed"};
  for (const auto& h : heuristics())
    for (const auto& s : h.params)
      if (s.kind != ParamSpec::Kind::Choice && std::find(names.begin(), names.end(), s.name) == names.end())
        names.push_back(s.name);
  return names;
}

std::vector<ParamSpec> common_params() {
  return {{"base", ParamSpec::Kind::Choice, "the heuristic that completes every tree (with its defaults)", 0, 0, 0,
           heuristic_names()},
          {"objective", ParamSpec::Kind::Choice,
           "what the kept tree minimises: fragments stored (ties by maximum depth), or depth (ties by fragments)", 0, 0,
           0, {"fragments", "depth"}}};
}

std::vector<ParamSpec> level_params(double width) {
  return {{"levels", ParamSpec::Kind::Integer, "the top levels whose nodes the search decides (the root is level 1)",
           2, 1, 64, {}},
          {"width", ParamSpec::Kind::Integer,
           "options tried per decided node: the base's choice and the fewest-split alternatives", width, 1, 64, {}}};
}

template <class... Lists>
std::vector<ParamSpec> joined(std::vector<ParamSpec> first, Lists... rest) {
  (first.insert(first.end(), rest.begin(), rest.end()), ...);
  return first;
}

}  // namespace

const std::vector<SearchInfo>& searches() {
  static const std::vector<SearchInfo> all = {
      {"restarts", "best of n builds by the base heuristic, each with another seed or value of one of its parameters",
       joined(common_params(),
              std::vector<ParamSpec>{
                  {"n", ParamSpec::Kind::Integer, "builds (the budget)", 4, 1, 1024, {}},
                  {"vary", ParamSpec::Kind::Choice, "what differs between the builds: the seed or a parameter of the base",
                   0, 0, 0, variable_names()},
                  {"from", ParamSpec::Kind::Real, "the varied parameter's first value", 0, -1e12, 1e12, {}},
                  {"to", ParamSpec::Kind::Real, "its last (geometric spacing when both are positive)", 1, -1e12, 1e12, {}}}),
       billed<restarts>, [](const ParamSet& p) { varied_spec(p); }},
      {"lookahead",
       "each top-level node takes the option whose completed tree is best, scored with the best option at its "
       "children (depth 1)",
       joined(common_params(), level_params(4),
              std::vector<ParamSpec>{{"depth", ParamSpec::Kind::Integer,
                                      "levels of options tried below each option before the base completes it", 1, 0,
                                      1, {}}}),
       billed<lookahead>, [](const ParamSet&) {}},
      {"beam", "beam search over partial trees: the best `beam` sets of top-level decisions, completed by the base",
       joined(common_params(), level_params(4),
              std::vector<ParamSpec>{{"beam", ParamSpec::Kind::Integer, "partial trees kept after each step", 4, 1, 256, {}}}),
       billed<beam>, [](const ParamSet&) {}},
  };
  return all;
}

const SearchInfo* find_search(std::string_view name) {
  for (const auto& s : searches())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace bsp
