#include "experiments/optimal/optimal.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/cpu_time.h"
#include "common/hash.h"
#include "experiments/reference_build.h"
#include "experiments/timing.h"

#include "geometry/segment2.h"
#include "metrics/expected_cost.h"
#include "split/registry.h"
#include "tree/build.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"
#include "validate/view_rays.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

double ratio(double value, double bound) { return bound > 0 ? value / bound : 0.0; }

HeuristicGap gap_of(const HeuristicChoice& h, double value, const OptimalResult& o) {
  HeuristicGap g;
  g.label = h.label;
  g.autopartition = h.autopartition();
  g.value = value;
  g.gap_lower = ratio(value, o.upper);
  g.gap_upper = ratio(value, o.lower);
  return g;
}

}  // namespace

bool certificate_agrees(double measured, double upper) {
  return std::abs(measured - upper) <= kCertificateRelative * std::max(1.0, std::abs(upper));
}

double objective_value(const Tree& tree, std::span<const Polygon> input, OptimalObjective objective, double margin) {
  if (objective == OptimalObjective::Fragments) return static_cast<double>(tree.fragments.size());
  const ExpectedCosts c = all_segments(input) ? planar_expected_costs(tree, margin) : expected_costs(tree, margin);
  return objective == OptimalObjective::EPoint ? c.e_point : c.e_line;
}

CheckedOptimum checked_optimum(std::span<const Polygon> input, const OptimalSettings& settings, std::uint32_t views) {
  CheckedOptimum out;
  const double start = thread_cpu_seconds();
  out.result = solve_optimal(input, settings);
  out.solve_cpu_seconds = thread_cpu_seconds() - start;
  const OptimalResult& o = out.result;
  out.certificate_value = objective_value(o.tree, input, o.objective, settings.cell_margin);
  out.invariant_violations = check_tree_invariants(o.tree, input).violations;
  ValidationSettings vs;
  vs.views = static_cast<int>(views);
  const ValidationReport order = all_segments(input)
                                     ? validate_segment_tree(o.tree, validation_eyes(o.tree.bounds, vs.views), vs)
                                     : validate_tree(o.tree, vs);
  out.order_violations = order.violations;
  out.rays = order.rays;
  return out;
}

GapComparison compare_with_optimum(std::span<const Polygon> input, const GapSettings& settings) {
  GapComparison out;
  CheckedOptimum checked = checked_optimum(input, settings.solver, settings.views);
  out.optimum = std::move(checked.result);
  out.certificate_value = checked.certificate_value;
  out.invariant_violations = checked.invariant_violations;
  out.order_violations = checked.order_violations;
  out.rays = checked.rays;
  const OptimalResult& o = out.optimum;
  BuildOptions options;
  options.shape = o.shape;
  for (const HeuristicChoice& h : settings.heuristics) {
    const Tree tree = h.build(input, options, settings.seed);
    out.gaps.push_back(gap_of(h, objective_value(tree, input, o.objective, settings.solver.cell_margin), o));
  }
  return out;
}

json to_json(const GapComparison& c) {
  const OptimalResult& o = c.optimum;
  const OptimalStats& s = o.stats;
  json gaps = json::array();
  for (const HeuristicGap& g : c.gaps)
    gaps.push_back({{"heuristic", g.label},
                    {"autopartition", g.autopartition},
                    {"value", g.value},
                    {"gap_lower", g.gap_lower},
                    {"gap_upper", g.gap_upper}});
  return {{"objective", objective_name(o.objective)},
          {"shape", shape_name(o.shape)},
          {"optimal", o.optimal()},
          {"lower", o.lower},
          {"upper", o.upper},
          {"greedy", o.greedy},
          {"certificate_value", c.certificate_value},
          {"certificate_fragments", o.tree.fragments.size()},
          {"certificate_nodes", o.tree.nodes.size()},
          {"invariant_violations", c.invariant_violations},
          {"order_violations", c.order_violations},
          {"order_rays", c.rays},
          {"solver",
           {{"states", s.states},
            {"expansions", s.expansions},
            {"candidates", s.candidates},
            {"memo_hits", s.memo_hits},
            {"fragments", s.fragments},
            {"planes", s.planes},
            {"seconds", s.seconds},
            {"out_of_time", s.out_of_time},
            {"out_of_states", s.out_of_states}}},
          {"heuristics", std::move(gaps)}};
}

namespace {

constexpr TimingField kTimings[] = {
    {"solve_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per solve of the instance, one per timed batch of at least 2 ms (timed once per process, shared by the instance's runs)"},
    {"solve_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the same input, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"solve_cpu_median", TimingRole::SamplesMedian, "the median of solve_cpu_samples"},
    {"solve_cpu_runs", TimingRole::SampleCount, "solves timed: depends on the machine's speed"},
    {"solve_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the solve whose tree the run checks, once per process"},
    {"build_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the heuristic's build"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};
constexpr std::string_view kGroupBy[] = {"objective"};
constexpr std::string_view kSizeGrowth[] = {"gap"};

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"scenes", "sizes", "heuristics", "seeds", "objectives", "shapes", "max_states", "seconds", "views"});
  auto b = std::make_unique<OptimalBlock>();
  std::vector<const GeneratorInfo*> sized;
  b->scenes = r.generator_names(r.required(j, path, "scenes"), child(path, "scenes"), "optimal", sized, true);
  b->sizes = r.generator_sizes(j, path, sized);
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  b->seeds = r.seeds(j, path);
  if (const json* list = r.optional(j, "objectives")) {
    b->objectives.clear();
    for (const auto& name : r.names(*list, child(path, "objectives"), "leave \"objectives\" out for fragments",
                                    [](const std::string& o) {
                                      if (!objective_named(o))
                                        throw UsageError("unknown objective '" + o + "' (known: fragments, e_point, e_line)");
                                    }))
      b->objectives.push_back(*objective_named(name));
  }
  if (const json* list = r.optional(j, "shapes")) {
    b->shapes.clear();
    for (const auto& name : r.names(*list, child(path, "shapes"), "leave \"shapes\" out for strict trees",
                                    [](const std::string& s) {
                                      if (!shape_named(s)) throw UsageError("unknown shape '" + s + "' (known: strict, coarse, leafy)");
                                    }))
      b->shapes.push_back(*shape_named(name));
  }
  if (const json* m = r.optional(j, "max_states")) b->max_states = r.integer(*m, child(path, "max_states"), 1, 1'000'000'000);
  if (const json* t = r.optional(j, "seconds")) b->seconds = r.real(*t, child(path, "seconds"), 0, 86'400, true);
  if (const json* v = r.optional(j, "views")) b->views = static_cast<std::uint32_t>(r.integer(*v, child(path, "views"), 1, kMaxViews));
  return b;
}

// An instance's optimum and the solver's timed batches beside their reference.
struct SharedOptimum {
  CheckedOptimum checked;
  TimedBatches batches;
};

// One solve (and one set of timed batches) per instance and process: every heuristic's job of the
// instance reads it. The batches are slowed by a slowdown planted on the label "optimal".
std::shared_ptr<const SharedOptimum> shared_optimum(const std::string& key, std::span<const Polygon> input,
                                                    const OptimalSettings& settings, std::uint32_t views,
                                                    const RunContext& context) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const SharedOptimum>> solved;
  {
    const std::lock_guard lock(mutex);
    if (auto it = solved.find(key); it != solved.end()) return it->second;
  }
  auto shared = std::make_shared<SharedOptimum>();
  shared->checked = checked_optimum(input, settings, views);
  const ReferenceBuild reference(input);
  if (shared->checked.result.stats.out_of_time) {
    // A solve that ran out of time measures its budget, not the code: one sample, the checked solve.
    shared->batches.samples = {shared->checked.solve_cpu_seconds};
    shared->batches.reference = {time_batch([&] { reference.run(); })};
    shared->batches.runs = 1;
  } else {
    shared->batches = time_batches([&] { solve_optimal(input, settings); }, context.slowdown("optimal"),
                                   [&] { reference.run(); });
  }
  const std::lock_guard lock(mutex);
  return solved.emplace(key, std::move(shared)).first->second;
}

bool has_objective(const json& id) { return id.contains("objective") && id["objective"].is_string(); }

}  // namespace

Jobs OptimalBlock::expand() const {
  Jobs out;
  for (const auto& name : scenes) {
    const GeneratorInfo& g = find_generator(name);
    for (auto n : sizes_in_range(g, sizes))
      for (const auto& h : choices_or_all(heuristics))
        for (auto seed : seeds)
          for (auto shape : shapes)
            for (auto objective : objectives)
              out.push_back(std::make_shared<OptimalJob>(SceneRun::generated(g, {}, h, shape, seed, n, views), objective,
                                                         max_states, seconds));
  }
  return out;
}

OptimalJob::OptimalJob(SceneRun scene, OptimalObjective objective, std::uint64_t max_states, double seconds)
    : scene_(std::move(scene)), objective_(objective), max_states_(max_states), seconds_(seconds) {
  Hasher h;
  h.add_string("optimal");
  h.add_string(scene_.hash(scene_.key_scene_text()));
  h.add_string(objective_name(objective_));
  h.add_u64(max_states_);
  h.add_double(seconds_);
  set_identity(h.hex(), scene_.n);
}

OptimalSettings OptimalJob::solver_settings() const {
  OptimalSettings s;
  s.objective = objective_;
  s.shape = scene_.shape;
  s.max_states = max_states_;
  s.seconds = seconds_;
  return s;
}

json OptimalJob::identity() const {
  json id = scene_.identity("optimal");
  id["command"] = "bspbench optimal" + scene_.scene_arguments() + " --seed " + std::to_string(scene_.seed) +
                  " --heuristic " + scene_.heuristic_label() + " --objective " + objective_name(objective_) + " --shape " +
                  shape_name(scene_.shape) + " --max-states " + std::to_string(max_states_) + " --seconds " +
                  exact_text(seconds_) + " --views " + std::to_string(scene_.views);
  id["objective"] = objective_name(objective_);
  id["max_states"] = max_states_;
  id["solver_seconds"] = seconds_;
  return id;
}

json OptimalJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const Scene scene = scene_.make_scene();
  const OptimalSettings settings = solver_settings();
  // The instance: everything but the heuristic.
  const std::string instance = scene_.scene + " " + scene_.key_scene_text() + " " + shape_name(scene_.shape) + " " +
                               objective_name(objective_) + " " + std::to_string(max_states_) + " " +
                               exact_text(seconds_) + " " + std::to_string(scene_.views);
  const auto shared = shared_optimum(instance, scene.polygons, settings, scene_.views, context);
  const CheckedOptimum* optimum = &shared->checked;
  const OptimalResult& o = optimum->result;
  BuildOptions options;
  options.shape = scene_.shape;
  const double build_start = thread_cpu_seconds();
  const Tree tree = scene_.heuristic->build(scene.polygons, options, scene_.seed);
  const double build_seconds = thread_cpu_seconds() - build_start;
  const HeuristicGap g = gap_of(*scene_.heuristic, objective_value(tree, scene.polygons, objective_, settings.cell_margin), o);
  json metrics{{"value", g.value},
               {"gap", g.gap_lower},
               {"gap_to_bound", o.lower > 0 ? json(g.gap_upper) : json(nullptr)},
               {"autopartition", g.autopartition ? 1 : 0},
               {"optimum_lower", o.lower},
               {"optimum_upper", o.upper},
               {"optimal", o.optimal() ? 1 : 0},
               {"greedy", o.greedy},
               {"certificate_value", optimum->certificate_value},
               {"fragments", tree.fragments.size()},
               {"nodes", tree.nodes.size()},
               {"solver_states", o.stats.states},
               {"solver_expansions", o.stats.expansions},
               {"out_of_states", o.stats.out_of_states ? 1 : 0},
               {"out_of_time", o.stats.out_of_time ? 1 : 0}};
  // The certificate must measure what the solver says it is worth: a difference is a violation.
  const bool agrees = certificate_agrees(optimum->certificate_value, o.upper);
  json invariants{{"violations", check_tree_invariants(tree, scene.polygons).violations +
                                     optimum->invariant_violations + (agrees ? 0 : 1)}};
  json validation{{"violations", optimum->order_violations}, {"rays", optimum->rays}};
  json timings{{"solve_cpu_samples", shared->batches.samples},
               {"solve_reference_samples", shared->batches.reference},
               {"solve_cpu_median", shared->batches.median()},
               {"solve_cpu_runs", shared->batches.runs},
               {"solve_cpu_seconds", optimum->solve_cpu_seconds},
               {"build_cpu_seconds", build_seconds}};
  json id = identity();
  id["n_polygons"] = scene.polygons.size();
  id["scene_hash"] = scene_json(scene)["hash"];
  return make_record(*this, std::move(id), std::move(metrics), std::move(invariants), std::move(validation), nullptr,
                     std::move(timings), start);
}

const Kind& optimal_kind() {
  static const Kind kind{
      .name = "optimal",
      .suite_key = "optimals",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .size_growth_metrics = kSizeGrowth,
      .timing_group_word = "optimal",
      .identity_ok = has_objective,
      .schema_section = "OPTIMAL RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
