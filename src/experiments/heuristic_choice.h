#pragma once
// A heuristic as a suite or a job names it: a registered name, "NAME", or a name with parameters,
// "NAME:k=v,k=v" (e.g. "weighted:candidates=0", the exhaustive variant). The name is a heuristic
// (split/registry.h) or a searching builder (search/tree_search.h, e.g. "beam:base=zennode"):
// both build trees through build(); only a heuristic has a splitter() for the commands that
// build per node (merging, updating, the exact kernel). The whole text is the
// label that names the runs in reports and in the gate's groups, so a variant is compared with
// itself only. Parsed and resolved against the registry once, when a job is made.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/hash.h"
#include "common/params.h"
#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/build_options.h"
#include "tree/tree.h"

namespace bsp::experiments {

// The label split into name and parameters, without the registry. Throws UsageError for a
// parameter without '=' ("weighted:candidates").
struct HeuristicLabel {
  std::string name;
  ParamAssignments params;
};
HeuristicLabel split_heuristic_label(const std::string& label);

struct HeuristicChoice {
  std::string label;
  std::string name;          // as registered
  bool search = false;       // a searching builder, not a heuristic
  ParamAssignments params;   // as the label gives them
  ParamSet resolved;         // every parameter, defaults included: what decides the trees

  // Throws UsageError for an unknown heuristic or a bad parameter.
  static HeuristicChoice parse(const std::string& label);
  // NAME with `params` (as a command's --heuristic and --param give them), labelled NAME:k=v,k=v.
  static HeuristicChoice of(const std::string& name, ParamAssignments params);
  // " --heuristic NAME --param k=v ...": how a command is told this choice (after
  // " --plugin PATH" when a plugin registered it).
  std::string arguments() const;
  // Throws UsageError for a search: it has no per-node splitter.
  std::unique_ptr<Splitter> splitter(std::uint64_t seed) const;
  // Throws UsageError for a search, naming `what` needs a heuristic; for checks where a job or a
  // command is read, before anything runs.
  void require_per_node(const std::string& what) const;
  // Whether every plane it picks is a fragment's (a search: its base's).
  bool autopartition() const;
  // The tree it builds from `input` with build_tree (a search builds several and keeps one).
  Tree build(std::span<const Polygon> input, const BuildOptions& options, std::uint64_t seed) const;
};

// What joins a job's key when a plugin registered the heuristic `name` (split/registry.h): the
// plugin's name, version and file hash. Built-ins add nothing, so their keys stay as they were.
void add_plugin_identity(Hasher& key, const std::string& name);
// " --plugin PATH" when a plugin registered `name`, else empty: the commands that repeat a job
// load it.
std::string plugin_arguments(const std::string& name);

// The parameters a heuristic or a search takes; throws UsageError naming both registries' names.
const std::vector<ParamSpec>& params_of(const std::string& name);

// The choices `labels` name, or every registered heuristic when there are none (so a heuristic
// added to the registry is swept without further wiring; searches, which cost many builds, only
// when named). Throws as parse does.
std::vector<HeuristicChoice> choices_or_all(const std::vector<std::string>& labels);
// choices_or_all for the kinds that build per node (`what`, e.g. "a merge block"): a search named
// there throws UsageError when the block is read.
std::vector<HeuristicChoice> per_node_choices_or_all(const std::vector<std::string>& labels, const std::string& what);
// make_splitter for a name a command was given: a search's name gets the searching builder's message.
std::unique_ptr<Splitter> per_node_splitter(const std::string& name, const ParamAssignments& params, std::uint64_t seed);

}  // namespace bsp::experiments
