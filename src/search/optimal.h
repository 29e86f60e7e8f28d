#pragma once
// Optimal autopartitions of small inputs, by branch and bound over the fragment sets of cells.
//
// The problem. An autopartition cuts each cell by the plane of one of its fragments (in 2D, the
// line of one of its segments). Among all autopartitions of an input with a given tree shape
// (tree.h), find one that minimises an objective:
//   - Fragments: the fragments the tree stores (the input plus one per split, minus slivers the
//     tolerance drops). Even deciding whether segments in the plane have an autopartition without
//     a cut is NP-hard [DeBergKhosravi2010], so this is for small inputs.
//   - EPoint, ELine: Naylor's expected costs [Naylor1993], exactly as metrics/expected_cost.h
//     computes them from the cells: per node, its cell's share of the root cell's volume (nodes
//     with a plane) or surface area (every node).
//
// The search. f(S) is the best objective of a subtree holding fragment set S (with its cell, for
// the cost objectives, whose terms depend on it):
//     f(S) = min over candidate planes P of S:  own(P) + f(front(S, P)) + f(back(S, P))
// with own(P) the node's own term (its coplanar fragments, or its cell's share). Subproblems are
// memoised, so one reached along two paths is solved once. For the fragments objective a
// subproblem is its fragment set (fragments interned by source and exact vertices), whatever its
// cell. For the cost objectives it is its cell, which decides the fragments it holds: a cell is
// keyed by the set of planes that bound its faces, so cuts made in another order, or by a plane a
// later cut made redundant, reach the same cell (keyed by exact vertices instead, whose faces are
// listed in the order of the cuts, the memo hardly ever hits: before the passes below, keying by
// planes moved the reach of the expected costs in 2D from 16 segments to 32). Every memo entry keeps an interval [lb, ub]: ub is achieved by a known subtree, lb
// is proved. Bounds [LandDoig1960]: before a subproblem is expanded its lb is admissible
// without search (its fragments too wide for the tolerance to drop; its own cell's term for the
// cost objectives); a candidate's bound
// is own(P) + lb(front) + lb(back), and a subproblem's lb is the least of its candidates'. A greedy
// tree (each cell cut by the candidate of least bound) gives every state it meets a first ub; the
// depth-first search then runs in passes under a target raised a step above the root's lb
// [Korf1985], each refining candidates in order of their bounds with the bound they must beat,
// until lb = ub at the root (optimal) or the budget runs out (an interval, never a silent
// approximation). After each pass a descent along the least-bound candidates keeps the tree it
// finds wherever that beats the incumbent.
//
// The certificate. The solver's choices are replayed through build_tree (tree/build.h), so the
// tree it returns is an ordinary tree that the tree invariants, the order check and the metrics
// measure independently; the caller compares their value with `upper`.
//
// Recursion. The search recurses over subproblems: each level uses up one plane of its input (its
// fragments stay in the node, or in the leafy shape can no longer part the set), so the depth is
// at most the input's distinct planes, which solve_optimal bounds by OptimalSettings::max_planes.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "geometry/polygon.h"
#include "tree/tree.h"

namespace bsp {

enum class OptimalObjective : std::uint8_t { Fragments, EPoint, ELine };
// "fragments", "e_point", "e_line": the names the CLI and every JSON use.
const char* objective_name(OptimalObjective o);
std::optional<OptimalObjective> objective_named(std::string_view name);

// Where a search stands after one of its passes (iterative deepening on the bound): what a progress
// line shows.
struct OptimalProgress {
  std::uint64_t passes = 0;
  double lower = 0, upper = 0;  // the root's bounds so far
  std::uint64_t states = 0;
  double seconds = 0;  // wall time since the search began
};

struct OptimalSettings {
  OptimalObjective objective = OptimalObjective::Fragments;
  Shape shape = Shape::Strict;
  // The expected costs' root cell margin, as MetricsSettings::cell_margin (expected_cost.h).
  double cell_margin = 0.01;
  // Budgets: the search stops after this many seconds of wall time, or once it holds this many
  // memoised subproblems (each a few hundred bytes with its candidates), and reports the interval.
  double seconds = 60;
  std::uint64_t max_states = 4'000'000;
  // Inputs with more distinct planes are refused (UsageError): far beyond what the search can
  // close, and the bound on its recursion depth.
  std::uint32_t max_planes = 256;
  // Called after each pass from the solving thread, when set (the CLI's progress line).
  std::function<void(const OptimalProgress&)> on_pass;
};

// What the search did. States and expansions measure the work; a solved instance of n fragments
// meets between n states (a greedy tree that the bounds prove optimal at once) and exponentially
// many (every subset of planes a cell can hold).
struct OptimalStats {
  std::uint64_t states = 0;      // memoised subproblems (fragment sets, with their cells for costs)
  std::uint64_t expansions = 0;  // subproblems whose candidates were partitioned
  std::uint64_t candidates = 0;  // candidate partitions computed
  std::uint64_t memo_hits = 0;   // children found already memoised
  std::uint64_t fragments = 0;   // distinct fragments interned
  std::uint64_t planes = 0;      // distinct candidate planes of the input (max_planes bounds them)
  double seconds = 0;
  bool out_of_time = false;
  bool out_of_states = false;
};

struct OptimalResult {
  OptimalObjective objective = OptimalObjective::Fragments;
  Shape shape = Shape::Strict;
  // No autopartition of this shape has a value below `lower`; `tree` has the value `upper`.
  // Fragments are integers; the expected costs are sums of doubles, so their bounds hold to the
  // rounding of those sums: a relative 1e-12 per level of the search, which `optimal` allows.
  double lower = 0;
  double upper = 0;
  double greedy = 0;  // the first incumbent: the greedy tree of least one-level bound
  bool optimal() const;
  Tree tree;  // the certificate: build_tree replaying the choices of `upper`
  OptimalStats stats;
};

// Throws UsageError for too many planes, or a flat scene with E_point / E_line and margin 0.
OptimalResult solve_optimal(std::span<const Polygon> input, const OptimalSettings& settings);

}  // namespace bsp
