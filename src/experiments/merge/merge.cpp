#include "experiments/merge/merge.h"

#include <algorithm>
#include <sstream>

#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/hash.h"
#include "experiments/merge/set_operation.h"
#include "experiments/reference_build.h"
#include "solid_pairs.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr std::uint64_t kMaxPoints = 100'000'000;  // as bspbench merge --points
constexpr std::uint64_t kDefaultPoints = 10000;

constexpr TimingField kTimings[] = {
    {"merge_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per merge (merge and reduce), one per timed batch of at least 2 ms (experiments/timing.h)"},
    {"merge_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the same input, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"merge_cpu_seconds", TimingRole::SamplesMedian, "the median of merge_cpu_samples"},
    {"merge_cpu_merges", TimingRole::SampleCount, "merges timed for the samples: depends on the machine's speed"},
    {"merge_seconds", TimingRole::Wall, "wall time of the first merge (the result that is checked), reduction excluded"},
    {"reduce_seconds", TimingRole::Wall, "wall time of the first merge's reduction"},
    {"build_a_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the first operand's solid tree (build and labels)"},
    {"build_b_cpu_seconds", TimingRole::Cpu, "thread CPU seconds of the second operand's solid tree"},
    {"corefine_seconds", TimingRole::Wall, "wall time of CGAL's corefinement of the same operands (the reference)"},
    {"check_seconds", TimingRole::Wall, "wall time of the proof against CGAL (points, volume, boundary)"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

// What aggregation groups by and fits growth of (experiments/kind.h).
constexpr std::string_view kGroupBy[] = {"operation", "kernel"};
constexpr std::string_view kGrowthMetrics[] = {"before_nodes", "after_nodes", "partition_nodes"};
constexpr std::string_view kGrowthTimings[] = {"merge_cpu_seconds", "merge_seconds"};

// Record fields from to_json(SolidCheck) (validate/solid_check.h).
// The boundary's closure: what must be zero, with what was done to close it. Volumes, not their
// relative errors: an error near 1e-16 is rounding noise that any change of summation order moves,
// while the volumes themselves compare within the gate's relative tolerance.
constexpr JsonField kInvariantFields[] = {{"border_edges", "/boundary/border_edges"},
                                           {"repeated_directed_edges", "/boundary/repeated_directed_edges"},
                                           {"t_junctions_split", "/boundary/t_junctions_split"},
                                           {"dropped_faces", "/boundary/dropped_faces"},
                                           {"boundary_volume", "/boundary/volume"}};
// Point membership and volume against CGAL: what must be zero, with what was counted apart.
constexpr JsonField kValidationFields[] = {{"points", "/points"},
                                            {"compared", "/compared"},
                                            {"mismatches", "/mismatches"},
                                            {"on_operand_surface", "/on_operand_surface"},
                                            {"within_plane_eps", "/within_plane_eps"},
                                            {"within_plane_eps_disagree", "/within_plane_eps_disagree"},
                                            {"corefine_volume", "/corefine_volume"},
                                            {"corefine_error", "/corefine_error"}};
constexpr JsonField kCheckMetricFields[] = {{"result_volume", "/tree_volume"}, {"boundary_faces", "/boundary/faces"}};

// {"a": {"b": 1}} as {"a_b": 1}, so aggregation summarises every field.
void flatten_into(const json& from, const std::string& prefix, json& out) {
  for (const auto& [k, v] : from.items()) {
    if (v.is_object()) flatten_into(v, prefix + k + "_", out);
    else out[prefix + k] = v;
  }
}

// Operand trees and merge cost, flat; the merge's wall times go to the timings.
json merge_metrics(const SetOperationRun& run, const json& check, json& timings) {
  json m = json::object();
  for (const auto& [prefix, o] : {std::pair{"a_", &run.operands.a}, std::pair{"b_", &run.operands.b}}) {
    m[std::string(prefix) + "fragments"] = o->fragments;
    flatten_into(to_json(solid_size(o->solid)), prefix, m);
  }
  flatten_into(to_json(run.stats), "", m);
  split_timings(m, timings, "", kTimings);
  pick_fields(check, kCheckMetricFields, m);
  return m;
}

json boundary_invariants(const SolidCheck& c, const json& check) {
  const bool volume_ok = c.boundary_volume_relative_error <= kVolumeRelativeTolerance;
  json out = json::object();
  pick_fields(check, kInvariantFields, out);
  out["violations"] = c.boundary.edges.border_edges + (volume_ok ? 0 : 1);
  return out;
}

json proof_validation(const SolidCheck& c, const json& check) {
  const bool volume_ok = c.corefine_error.empty() && c.volume_relative_error <= kVolumeRelativeTolerance;
  json out = json::object();
  pick_fields(check, kValidationFields, out);
  out["violations"] = c.mismatches + (volume_ok ? 0 : 1);
  return out;
}

std::array<SolidOperand, 2> operands(const MergeSpec& s) { return find_solid_pair(s.pair).operands(s.n, s.seed); }

ParamSet operand_params(const SolidOperand& o) {
  return ParamSet::resolve(find_generator(o.scene).params, o.params, "scene " + o.scene);
}

Scene operand_scene(const SolidOperand& o) {
  Scene scene = make_scene(o.scene, o.params);
  check_scene(scene, "scene " + scene.name);
  return scene;
}

std::string command(const MergeSpec& s) {
  std::string out = "bspbench merge";
  const auto ops = operands(s);
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string which = i == 0 ? "--a" : "--b";
    out += " " + which + " " + ops[i].scene;
    for (const auto& [k, v] : ops[i].params) out += " " + which + "-param " + k + "=" + v;
  }
  return out + " --op " + std::string(set_op_name(s.op)) + s.heuristic.arguments() + " --seed " +
         std::to_string(s.seed) + " --points " + std::to_string(s.points) +
         (s.kernel == Kernel::Exact ? " --kernel exact" : "");
}

// The key: the pair, both operands as resolved, the heuristic, the operation, the seed and the
// points checked.
std::string merge_key(const MergeSpec& s) {
  Hasher h;
  h.add_string("merge");
  h.add_string(s.pair);
  for (const auto& o : operands(s)) {
    h.add_string(o.scene);
    h.add_string(operand_params(o).canonical());
  }
  h.add_string(s.heuristic.label);
  h.add_string(s.heuristic.resolved.canonical());
  add_plugin_identity(h, s.heuristic.name);
  h.add_string(set_op_name(s.op));
  h.add_u64(s.seed);
  h.add_u64(s.points);
  if (s.kernel != Kernel::Float) h.add_string(kernel_name(s.kernel));  // float keys stay as they were
  return h.hex();
}

// What reports must hold of a merge run's identity: its operation and two operands.
bool operation_and_operands(const json& id) {
  return id.contains("operation") && id["operation"].is_string() && id.contains("operands") &&
         id["operands"].is_array() && id["operands"].size() == 2;
}

// ---- the block ----

std::vector<std::uint64_t> pair_sizes(const SolidPairInfo& pair, const MergeBlock& block) {
  if (!pair.sized) return {0};
  std::vector<std::uint64_t> out;
  for (auto s : block.sizes)
    if (static_cast<double>(s) >= pair.min_n && static_cast<double>(s) <= pair.max_n) out.push_back(s);
  return out;
}

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"pairs", "heuristics", "ops", "sizes", "seeds", "points", "kernels"});
  auto b = std::make_unique<MergeBlock>();
  std::vector<const SolidPairInfo*> chosen;
  if (const json* pairs = r.optional(j, "pairs")) {
    b->pairs = r.names(*pairs, child(path, "pairs"), "leave \"pairs\" out to run every solid pair",
                       [](const std::string& name) { find_solid_pair(name); });
    for (const auto& name : b->pairs) chosen.push_back(&find_solid_pair(name));
  } else {
    for (const auto& pair : solid_pairs()) chosen.push_back(&pair);
  }
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  if (const json* ops = r.optional(j, "ops")) {
    for (const auto& name : r.names(*ops, child(path, "ops"), "leave \"ops\" out for all four",
                                    [](const std::string& op) { parse_set_op(op); }))
      b->ops.push_back(parse_set_op(name));
  }
  const bool any_sized = std::any_of(chosen.begin(), chosen.end(), [](const SolidPairInfo* p) { return p->sized; });
  if (const json* s = r.optional(j, "sizes")) {
    const std::string p = child(path, "sizes");
    if (!any_sized) r.fail(p, "no pair of this block takes a size");
    b->sizes = r.sizes(*s, p);
    if (r.optional(j, "pairs"))
      for (const auto* pair : chosen)
        for (std::size_t i = 0; pair->sized && i < b->sizes.size(); ++i) {
          const auto n = static_cast<double>(b->sizes[i]);
          if (n < pair->min_n || n > pair->max_n) {
            std::ostringstream range;
            range << "[" << pair->min_n << ", " << pair->max_n << "]";
            r.fail(element(p, i), std::to_string(b->sizes[i]) + " is outside " + pair->name +
                                      "'s range of polygons per operand, " + range.str());
          }
        }
  } else if (any_sized) {
    r.fail(path, "missing key 'sizes' (polygons per operand)");
  }
  b->seeds = r.seeds(j, path);
  b->kernels = r.kernels(j, path);
  b->points = kDefaultPoints;
  if (const json* points = r.optional(j, "points")) b->points = r.integer(*points, child(path, "points"), 0, kMaxPoints);
  return b;
}

}  // namespace

Jobs MergeBlock::expand() const {
  std::vector<std::string> names = pairs;
  if (names.empty())
    for (const auto& p : solid_pairs()) names.push_back(p.name);
  const std::vector<SetOp> all_ops = ops.empty() ? std::vector<SetOp>{SetOp::Union, SetOp::Intersection,
                                                                      SetOp::Difference, SetOp::SymmetricDifference}
                                                 : ops;
  Jobs out;
  for (const auto& name : names) {
    const SolidPairInfo& pair = find_solid_pair(name);
    for (auto n : pair_sizes(pair, *this))
      for (const auto& h : per_node_choices_or_all(heuristics, "a merge block"))
        for (auto op : all_ops)
          for (auto kernel : kernels)
            for (auto seed : seeds)
              out.push_back(std::make_shared<MergeJob>(MergeSpec{pair.name, n, h, op, seed, points, kernel}));
  }
  return out;
}

MergeJob::MergeJob(MergeSpec spec) : spec_(std::move(spec)) { set_identity(merge_key(spec_), spec_.n); }

nlohmann::json MergeJob::identity() const {
  json ops = json::array();
  for (const auto& o : operands(spec_)) ops.push_back({{"scene", o.scene}, {"params", operand_params(o).to_json()}});
  // The pair's parameters as given: n when the pair is sized, and the seed.
  json pair_params = json::object();
  if (spec_.n > 0) pair_params["n"] = spec_.n;
  pair_params["seed"] = spec_.seed;
  json id = {{"kind", "merge"},
          {"scene", spec_.pair},
          {"scene_params", std::move(pair_params)},
          {"operands", std::move(ops)},
          {"heuristic", spec_.heuristic.label},
          {"heuristic_params", spec_.heuristic.resolved.to_json()},
          {"operation", set_op_name(spec_.op)},
          {"build", "recursive"},
          {"shape", shape_name(Shape::Strict)},
          {"seed", spec_.seed},
          {"n", spec_.n},
          {"points", spec_.points},
          {"command", command(spec_)}};
  if (spec_.kernel != Kernel::Float) id["kernel"] = kernel_name(spec_.kernel);
  return id;
}

namespace {

json exact_operand_metrics(const ExactSetOperationRun& run) {
  json m = json::object();
  for (const auto& [prefix, o] : {std::pair{"a_", &run.operands.a}, std::pair{"b_", &run.operands.b}}) {
    m[std::string(prefix) + "fragments"] = o->fragments;
    flatten_into(to_json(solid_size(o->solid)), prefix, m);
  }
  return m;
}

// The exact kernel's record: the same fields where they mean the same, the exact answers beside
// them (validate/exact_solid_check.h): border edges are the boundary's exact border segments, and
// the volume check is equality of rationals. A rational's text runs to thousands of digits, so the
// record keeps its length and a hash (`bspbench merge --kernel exact --json` prints it whole).
constexpr JsonField kExactInvariantFields[] = {{"border_edges", "/boundary/border_edges"},
                                               {"boundary_volume", "/boundary/volume"}};

void exact_volumes(const ExactSolidCheck& c, json& validation) {
  validation["volume_equal"] = c.volume_equal();
  for (const auto& [name, text] : {std::pair{"volume_exact", &c.boundary.volume},
                                   std::pair{"corefine_volume_exact", &c.corefine_volume}}) {
    Hasher h;
    h.add_string(*text);
    validation[std::string(name) + "_hash"] = h.hex();
    validation[std::string(name) + "_chars"] = text->size();
  }
}

}  // namespace

json MergeJob::run_exact(const RunContext& context, const Scene& a, const Scene& b, double start) const {
  const auto splitter = spec_.heuristic.splitter(spec_.seed);
  SolidCheckSettings settings;
  settings.points = spec_.points;
  settings.seed = spec_.seed;
  json timings = json::object();
  double check_start = 0;
  const ExactSetOperationRun run =
      run_exact_set_operation(a, b, spec_.op, *splitter, settings, [&](ExactSolidOperands& o) {
        std::vector<Polygon> both = a.polygons;
        both.insert(both.end(), b.polygons.begin(), b.polygons.end());
        const ReferenceBuild reference(both);
        const TimedBatches batches = time_batches(
            [&] { discard(merge(o.a.solid, o.b.solid, *o.space, spec_.op), o.a.solid, o.b.solid, *o.space); },
            context.slowdown(spec_.heuristic.label), [&] { reference.run(); });
        timings["merge_cpu_samples"] = batches.samples;
        timings["merge_reference_samples"] = batches.reference;
        timings["merge_cpu_merges"] = batches.runs;
        timings["merge_cpu_seconds"] = batches.median();
        check_start = wall_seconds();
      });
  timings["check_seconds"] = wall_seconds() - check_start;
  timings["build_a_cpu_seconds"] = run.operands.a_cpu_seconds;
  timings["build_b_cpu_seconds"] = run.operands.b_cpu_seconds;
  timings["corefine_seconds"] = run.check.corefine_seconds;
  const json check = to_json(run.check);
  json id = identity();
  id["n_polygons"] = a.polygons.size() + b.polygons.size();
  for (std::size_t i = 0; i < 2; ++i) {
    const Scene& s = i == 0 ? a : b;
    id["operands"][i]["n_polygons"] = s.polygons.size();
    id["operands"][i]["scene_hash"] = scene_json(s)["hash"];
  }
  json metrics = exact_operand_metrics(run);
  flatten_into(to_json(run.stats), "", metrics);
  split_timings(metrics, timings, "", kTimings);
  pick_fields(check, kCheckMetricFields, metrics);
  json invariants = json::object();
  pick_fields(check, kExactInvariantFields, invariants);
  invariants["violations"] = run.check.boundary.border_segments;
  json validation = json::object();
  pick_fields(check, kValidationFields, validation);
  exact_volumes(run.check, validation);
  validation["violations"] = run.check.mismatches + (run.check.volume_equal() ? 0 : 1);
  return make_record(*this, std::move(id), std::move(metrics), std::move(invariants), std::move(validation), nullptr,
                     std::move(timings), start);
}

nlohmann::json MergeJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const auto specs = operands(spec_);
  const Scene a = operand_scene(specs[0]), b = operand_scene(specs[1]);
  if (spec_.kernel == Kernel::Exact) return run_exact(context, a, b, start);
  const auto splitter = spec_.heuristic.splitter(spec_.seed);
  SolidCheckSettings settings;
  settings.points = spec_.points;
  settings.seed = spec_.seed;
  json timings = json::object();
  double check_start = 0;
  const SetOperationRun run = run_set_operation(a, b, spec_.op, *splitter, settings, [&](const SolidOperands& o) {
    std::vector<Polygon> both = a.polygons;
    both.insert(both.end(), b.polygons.begin(), b.polygons.end());
    const ReferenceBuild reference(both);
    const TimedBatches batches = time_batches([&] { merge(o.a.solid, o.b.solid, spec_.op); },
                                              context.slowdown(spec_.heuristic.label), [&] { reference.run(); });
    timings["merge_cpu_samples"] = batches.samples;
    timings["merge_reference_samples"] = batches.reference;
    timings["merge_cpu_merges"] = batches.runs;
    timings["merge_cpu_seconds"] = batches.median();
    check_start = wall_seconds();
  });
  timings["check_seconds"] = wall_seconds() - check_start;
  timings["build_a_cpu_seconds"] = run.operands.a_cpu_seconds;
  timings["build_b_cpu_seconds"] = run.operands.b_cpu_seconds;
  timings["corefine_seconds"] = run.check.corefine_seconds;
  const json check = to_json(run.check);
  json id = identity();
  id["n_polygons"] = a.polygons.size() + b.polygons.size();
  for (std::size_t i = 0; i < 2; ++i) {
    const Scene& s = i == 0 ? a : b;
    id["operands"][i]["n_polygons"] = s.polygons.size();
    id["operands"][i]["scene_hash"] = scene_json(s)["hash"];
  }
  json metrics = merge_metrics(run, check, timings);
  return make_record(*this, std::move(id), std::move(metrics), boundary_invariants(run.check, check),
                     proof_validation(run.check, check), nullptr, std::move(timings), start);
}

const Kind& merge_kind() {
  static const Kind kind{
      .name = "merge",
      .suite_key = "merges",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .timing_group_field = "operation",
      .identity_ok = operation_and_operands,
      .schema_section = "MERGE RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
