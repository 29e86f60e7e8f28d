#pragma once
// Searching builders: they build many trees and keep the best, so they choose more than one plane
// per node, which a Splitter may not (splitter.h). They live in their own registry, beside the
// heuristics' (split/registry.h), and are named like heuristics everywhere a tree is built from a
// name ("beam:width=4,base=zennode"); experiments/heuristic_choice.h resolves a name in both.
//
// Every search completes the trees it compares with a base heuristic, decides the nodes of the
// top `levels` levels (decisions.h), and keeps the tree that is best by its objective: the
// fragments stored, ties by maximum depth ("fragments"), or the other way round ("depth"). The
// budget of each is its number of full builds, given below per strategy; each parameter that sets
// it is a knob of cost against quality.
//
//   restarts   best of n builds by the base, each with another seed or another value of one of the
//              base's parameters (the multi-tree idea of [ZokumBSP]); n builds.
//   lookahead  top-down over the top levels: each candidate of a node is scored by the tree the
//              base completes below it, improved by the best alternative at each of its children
//              when depth = 1 (the pilot method [DuinVoss1999] with a one-level lookahead);
//              (width − 1)·(1 + 2·width) builds per decided node, width − 1 with depth = 0.
//   beam       beam search over partial trees [Lowerre1976]: the `beam` best sets of decisions,
//              each extended at its next undecided node by every option there; at most
//              beam·(width − 1) builds per step, a step per decided node of the best state.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"
#include "geometry/polygon.h"
#include "tree/build_options.h"
#include "tree/tree.h"

namespace bsp {

struct SearchInfo {
  std::string name;
  std::string summary;  // one line, as a heuristic's
  std::vector<ParamSpec> params;
  std::function<Tree(std::span<const Polygon>, const BuildOptions&, const ParamSet&, std::uint64_t seed)> build;
  // Throws UsageError for parameters that resolve but do not fit together (restarts varying a
  // parameter its base lacks), so a suite or a command fails when it is read, not mid-run.
  std::function<void(const ParamSet&)> check;
};

const std::vector<SearchInfo>& searches();
// Null when `name` is no search.
const SearchInfo* find_search(std::string_view name);

}  // namespace bsp
