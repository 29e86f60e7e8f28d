#include "experiments/csg/csg.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "common/hash.h"
#include "experiments/csg/evaluate.h"
#include "experiments/csg/peers.h"
#include "experiments/reference_build.h"
#include "scene/scene.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr std::uint64_t kMaxPoints = 100'000'000;
constexpr std::uint64_t kDefaultPoints = 2000;
constexpr const char* kDefaultHeuristic = "octree";

constexpr TimingField kTimings[] = {
    {"evaluate_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per evaluation mesh in to mesh out (leaf builds, merges, boundary), one per timed batch of at least 2 ms (experiments/timing.h)"},
    {"evaluate_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of all the program's leaves, one batch before each timed batch: the gate divides each sample by it"},
    {"evaluate_cpu_seconds", TimingRole::SamplesMedian, "the median of evaluate_cpu_samples"},
    {"evaluate_cpu_runs", TimingRole::SampleCount, "evaluations timed: depends on the machine's speed"},
    {"build_seconds", TimingRole::Wall, "wall time of the first evaluation's leaf builds"},
    {"merge_seconds", TimingRole::Wall, "wall time of its merges (and hulls)"},
    {"boundary_seconds", TimingRole::Wall, "wall time of its boundary extraction and welding"},
    {"seconds", TimingRole::Wall, "the first evaluation mesh in to mesh out: builds, merges and boundary"},
    {"input_check_seconds", TimingRole::Wall, "wall time proving the leaves closed and free of self-intersections"},
    {"reference_seconds", TimingRole::Wall, "wall time of CGAL's step-by-step evaluation in the proof (corefinement, or Nef polyhedra)"},
    {"check_seconds", TimingRole::Wall, "wall time of the whole proof (points, volume, boundary)"},
    {"peer_seconds", TimingRole::Wall, "a peer's time mesh in to mesh out as peers.h states it (OpenSCAD's includes its process)"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

constexpr std::string_view kGroupBy[] = {"engine", "kernel"};
constexpr std::string_view kGrowthMetrics[] = {"partition_calls", "result_nodes"};
constexpr std::string_view kGrowthTimings[] = {"evaluate_cpu_seconds"};

const char* engine_kernel(const CsgSpec& s) { return s.engine == "bspbench" ? kernel_name(s.kernel) : "none"; }

std::string csg_key(const CsgSpec& s) {
  Hasher h;
  h.add_string("csg");
  h.add_string(s.program.label());
  h.add_string(s.engine);
  if (s.engine == "bspbench") {
    h.add_string(s.heuristic.label);
    h.add_string(s.heuristic.resolved.canonical());
    add_plugin_identity(h, s.heuristic.name);
    h.add_string(kernel_name(s.kernel));
    h.add_u64(s.points);
  }
  h.add_u64(s.seed);
  return h.hex();
}

std::string command(const CsgSpec& s) {
  if (s.engine != "bspbench") return "bspbench sweep (a csg block with engine " + s.engine + ")";
  return "bspbench csg " + s.program.label() + s.heuristic.arguments() + " --kernel " + kernel_name(s.kernel) + " --seed " +
         std::to_string(s.seed) + " --points " + std::to_string(s.points);
}

bool has_engine(const json& id) { return id.contains("engine") && id["engine"].is_string() && id.contains("program"); }

// ---- the bspbench engine's record ----

// The merge cost of the whole program: every step's counters summed, the largest result.
json merge_cost(const CsgEvaluation& e) {
  std::uint64_t merges = 0, calls = 0, nodes = 0, splits = 0, steps_nodes = 0, largest = 0;
  for (const CsgStepCost& s : e.steps) {
    merges += s.merges;
    calls += s.stats.partition_calls;
    nodes += s.stats.partition_nodes;
    splits += s.stats.shp_splits;
    steps_nodes += s.stats.merge_nodes;
    largest = std::max(largest, s.stats.before.nodes);
  }
  std::uint64_t leaf_nodes = 0, fragments = 0;
  for (const CsgLeafCost& l : e.leaves) leaf_nodes += l.size.nodes, fragments += l.fragments;
  return {{"leaves_built", e.leaves.size()}, {"leaf_nodes", leaf_nodes},   {"leaf_fragments", fragments},
          {"steps", e.steps.size()},         {"merges", merges},           {"partition_calls", calls},
          {"partition_nodes", nodes},        {"shp_splits", splits},       {"merge_nodes", steps_nodes},
          {"largest_step_nodes", largest},   {"result_nodes", e.result.nodes}, {"result_depth", e.result.depth},
          {"result_faces", e.mesh.face_count()}, {"result_vertices", e.mesh.vertices.size()},
          {"dropped_input", e.dropped_input}, {"volume", e.check.volume}};
}

json proof(const ProgramCheck& c) {
  const json j = to_json(c);
  json v = {{"points", c.points},        {"compared", c.compared},   {"mismatches", c.mismatches},
            {"on_operand_surface", c.on_operand}, {"within_plane_eps", c.within_eps},
            {"within_plane_eps_disagree", c.within_eps_disagree}, {"reference", c.reference},
            {"reference_volume", c.corefine_volume}, {"volume_relative_error", j["volume_relative_error"]},
            {"corefine_refused", c.corefine_refused}, {"reference_error", c.corefine_error},
            {"volume_ok", c.volume_ok()}};
  if (c.exact) {
    for (const auto& [name, text] : {std::pair{"volume_exact", &c.volume_exact}, std::pair{"reference_volume_exact", &c.corefine_volume_exact}}) {
      Hasher h;
      h.add_string(*text);
      v[std::string(name) + "_hash"] = h.hex();
    }
  }
  v["violations"] = c.mismatches + (c.volume_ok() ? 0 : 1);
  return v;
}

std::vector<Polygon> all_leaves(const csg::Postfix& p) {
  std::vector<Polygon> out;
  for (const csg::Leaf& leaf : p.leaves) out.insert(out.end(), leaf.polygons.begin(), leaf.polygons.end());
  return out;
}

// ---- the block ----

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"programs", "engines", "heuristics", "kernels", "seeds", "points", "peer_timeout"});
  auto b = std::make_unique<CsgBlock>();
  const std::string programs = child(path, "programs");
  r.each(r.required(j, path, "programs"), programs, "name at least one program",
         [&](const json& p, const std::string& at) {
           const std::string text = r.string(p, at);
           b->programs.push_back(r.at(at, [&] { return parse_program_source(text); }));
         });
  if (const json* e = r.optional(j, "engines"))
    b->engines = r.names(*e, child(path, "engines"), "leave \"engines\" out for bspbench alone", [](const std::string& name) {
      if (name != "bspbench" && !is_peer(name)) throw UsageError("unknown engine '" + name + "' (bspbench, cgal, openscad, manifold)");
    });
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = r.heuristics(*h, child(path, "heuristics"));
  if (r.optional(j, "kernels")) b->kernels = r.kernels(j, path);
  b->seeds = r.seeds(j, path);
  b->points = kDefaultPoints;
  if (const json* points = r.optional(j, "points")) b->points = r.integer(*points, child(path, "points"), 0, kMaxPoints);
  b->peer_timeout = kDefaultPeerTimeout;
  if (const json* t = r.optional(j, "peer_timeout")) b->peer_timeout = r.real(*t, child(path, "peer_timeout"), 0, 86400, true);
  return b;
}

}  // namespace

Jobs CsgBlock::expand() const {
  Jobs out;
  const std::vector<HeuristicChoice> choices = per_node_choices_or_all(heuristics.empty() ? std::vector<std::string>{kDefaultHeuristic} : heuristics, "a csg block");
  for (const ProgramSource& program : programs)
    for (const std::string& engine : engines)
      for (const std::uint64_t seed : seeds) {
        // A program that is not generated is the same for every seed: its peers run once.
        if (engine != "bspbench" && !program.generated() && seed != seeds.front()) continue;
        if (engine != "bspbench") {
          out.push_back(std::make_shared<CsgJob>(CsgSpec{program, engine, {}, Kernel::Exact, seed, 0, peer_timeout}));
          continue;
        }
        for (const HeuristicChoice& h : choices)
          for (const Kernel kernel : kernels)
            out.push_back(std::make_shared<CsgJob>(CsgSpec{program, engine, h, kernel, seed, points, 0}));
      }
  return out;
}

CsgJob::CsgJob(CsgSpec spec) : spec_(std::move(spec)) { set_identity(csg_key(spec_), spec_.program.k); }

json CsgJob::identity() const {
  json params = json::object();
  if (spec_.program.generated()) params["k"] = spec_.program.k;
  params["seed"] = spec_.seed;
  const bool ours = spec_.engine == "bspbench";
  return {{"kind", "csg"},
          {"scene", spec_.program.generated() ? spec_.program.name : spec_.program.label()},
          {"scene_params", params},
          {"program", spec_.program.label()},
          {"engine", spec_.engine},
          {"heuristic", ours ? spec_.heuristic.label : "peer:" + spec_.engine},
          {"heuristic_params", ours ? spec_.heuristic.resolved.to_json() : json::object()},
          {"kernel", engine_kernel(spec_)},
          {"build", "recursive"},
          {"shape", "strict"},
          {"seed", spec_.seed},
          {"n", spec_.program.k},
          {"points", spec_.points},
          {"command", command(spec_)}};
}

json CsgJob::run_peer_job(const LoadedProgram& loaded, const std::filesystem::path& scratch, double start) const {
  const PeerResult r = run_peer(spec_.engine, loaded.file, loaded.postfix, scratch, PeerSettings{spec_.peer_timeout, self_executable()});
  json id = identity();
  id["peer"] = {{"version", r.version}, {"threads", r.threads}, {"timeout", spec_.peer_timeout}};
  id["n_polygons"] = all_leaves(loaded.postfix).size();
  json metrics = {{"leaves", loaded.postfix.leaves.size()}, {"volume", r.volume}, {"result_triangles", r.triangles},
                  {"volume_rounding_bound", r.volume_rounding_bound}};
  // A peer's failure is a fact about it, recorded, never a violation of ours.
  json validation = {{"status", r.status}, {"note", r.note}, {"violations", 0}};
  json timings = {{"peer_seconds", r.seconds}};
  return make_record(*this, std::move(id), std::move(metrics), json{{"violations", 0}}, std::move(validation), nullptr,
                     std::move(timings), start);
}

json CsgJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const auto scratch = scratch_folder(key());
  struct Cleanup {
    std::filesystem::path dir;
    ~Cleanup() { std::filesystem::remove_all(dir); }
  } cleanup{scratch};
  const LoadedProgram loaded = load_program(spec_.program, spec_.seed, scratch);
  if (spec_.engine != "bspbench") return run_peer_job(loaded, scratch, start);

  CsgSettings settings;
  settings.kernel = spec_.kernel;
  settings.check.points = spec_.points;
  settings.check.seed = spec_.seed;
  const auto splitter = spec_.heuristic.splitter(spec_.seed);
  const CsgEvaluation e = evaluate_program(loaded.program, loaded.postfix, *splitter, settings);
  CsgSettings unproved = settings;  // the timed part alone: leaves already checked, no proof
  unproved.prove = false;
  unproved.check_inputs = false;
  const std::vector<Polygon> leaves = all_leaves(loaded.postfix);
  const ReferenceBuild reference(leaves);
  const TimedBatches batches = time_batches(
      [&] {
        const auto s = spec_.heuristic.splitter(spec_.seed);
        evaluate_program(loaded.program, loaded.postfix, *s, unproved);
      },
      context.slowdown(spec_.heuristic.label), [&] { reference.run(); });
  json timings = {{"evaluate_cpu_samples", batches.samples}, {"evaluate_reference_samples", batches.reference},
                  {"evaluate_cpu_runs", batches.runs},      {"evaluate_cpu_seconds", batches.median()},
                  {"build_seconds", e.build_seconds},       {"merge_seconds", e.merge_seconds},
                  {"boundary_seconds", e.boundary_seconds}, {"seconds", e.seconds()},
                  {"input_check_seconds", e.check_seconds}, {"reference_seconds", e.check.corefine_seconds},
                  {"check_seconds", e.proof_seconds}};
  json id = identity();
  id["n_polygons"] = leaves.size();
  id["program_hash"] = content_hash(Scene{"", {}, leaves, {}});
  json invariants = {{"border_edges", e.check.border_edges}, {"boundary_faces", e.check.boundary_faces},
                     {"violations", e.check.border_edges}};
  return make_record(*this, std::move(id), merge_cost(e), std::move(invariants), proof(e.check), nullptr, std::move(timings),
                     start);
}

const Kind& csg_kind() {
  static const Kind kind{
      .name = "csg",
      .suite_key = "csg",
      .parse = parse_block,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .timing_group_field = "engine",
      .identity_ok = has_engine,
      .schema_section = "CSG RUN",
  };
  return kind;
}

}  // namespace bsp::experiments
