#pragma once
// Optimality gaps: each heuristic's tree beside the optimal autopartition of the same small scene
// (search/optimal.h), for one objective and tree shape. The optimum is an interval [lower, upper]
// when the solver's budget ran out; a heuristic's gap is its value divided by each end (equal when
// the optimum is proved). A heuristic that cuts by free planes (halving, octree, sah) is not an
// autopartition and can beat the autopartition optimum: its gap says so with `autopartition`
// false. The optimum's tree is the certificate: its value is measured again here by the metrics
// (tree size, metrics/expected_cost.h), and its invariants and back-to-front order are checked
// against Embree, like any heuristic's tree. `bspbench optimal` prints one comparison.
//
// In a suite, an "optimals" block (analysis/SUITE_SCHEMA.md) names small scenes of any family (2D
// ones too), sizes, seeds, heuristics, objectives and shapes; each job is one heuristic on one
// instance, and its record (analysis/SCHEMA.md, OPTIMAL RUN) holds the heuristic's value, the
// optimum's interval and the gaps. The jobs of one instance share one solve per process. The
// solver's budget in a suite is its count of states, which keeps records deterministic; its time
// budget is a safety net whose expiry the record reports (out_of_time).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "experiments/heuristic_choice.h"
#include "experiments/kind.h"
#include "experiments/scene_run.h"
#include "geometry/polygon.h"
#include "search/optimal.h"
#include "tree/tree.h"

namespace bsp::experiments {

// How far the certificate's measured value may lie from the solver's: none for fragments; for the
// expected costs, the rounding of sums taken in another order.
inline constexpr double kCertificateRelative = 1e-9;
// Whether `measured` (the metrics' value of the optimum's tree) agrees with the solver's `upper`.
bool certificate_agrees(double measured, double upper);

struct GapSettings {
  OptimalSettings solver;
  std::vector<HeuristicChoice> heuristics;  // compared with the optimum (choices_or_all)
  std::uint64_t seed = 1;                   // the heuristics' randomness
  std::uint32_t views = 8;                  // eyes the certificate's order is checked from
};

// The objective's value of any tree of `input`, as the solver counts it: stored fragments, or
// E_point / E_line over the root cell of `margin` (planar_expected_costs for a 2D scene).
double objective_value(const Tree& tree, std::span<const Polygon> input, OptimalObjective objective, double margin);

struct HeuristicGap {
  std::string label;
  bool autopartition = true;
  double value = 0;
  double gap_lower = 0, gap_upper = 0;  // value / upper and value / lower (0 when the bound is 0: no gap known)
};

struct GapComparison {
  OptimalResult optimum;
  double certificate_value = 0;  // the certificate measured by the metrics: equals optimum.upper
  std::uint64_t invariant_violations = 0;
  std::uint64_t order_violations = 0;
  std::uint64_t rays = 0;
  std::vector<HeuristicGap> gaps;
};

GapComparison compare_with_optimum(std::span<const Polygon> input, const GapSettings& settings);

nlohmann::json to_json(const GapComparison& c);

// The optimum of one scene, solved with `settings` and checked as compare_with_optimum checks it.
struct CheckedOptimum {
  OptimalResult result;
  double certificate_value = 0;
  std::uint64_t invariant_violations = 0, order_violations = 0, rays = 0;
  double solve_cpu_seconds = 0;
};
CheckedOptimum checked_optimum(std::span<const Polygon> input, const OptimalSettings& settings, std::uint32_t views);

struct OptimalBlock final : Block {
  std::vector<std::string> scenes;  // generators, 2D ones included
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<std::uint64_t> seeds;
  std::vector<OptimalObjective> objectives = {OptimalObjective::Fragments};
  std::vector<Shape> shapes = {Shape::Strict};
  std::uint64_t max_states = 1'000'000;
  double seconds = 600;
  std::uint32_t views = 4;

  Jobs expand() const override;
};

class OptimalJob final : public Job {
 public:
  OptimalJob(SceneRun scene, OptimalObjective objective, std::uint64_t max_states, double seconds);
  std::string_view kind() const override { return "optimal"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& scene() const { return scene_; }

 private:
  OptimalSettings solver_settings() const;
  SceneRun scene_;
  OptimalObjective objective_;
  std::uint64_t max_states_;
  double seconds_;
};

const Kind& optimal_kind();

}  // namespace bsp::experiments
