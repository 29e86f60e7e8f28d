// bspbench csg FILE.csg: an OpenSCAD CSG program evaluated by successive merges of solid trees
// (experiments/csg/evaluate.h), the merge cost of every step printed, the result proved against
// CGAL's corefinement of the same polyhedra step by step, and its boundary optionally written.
// Exit code 1 when the proof fails, 2 for a program bspbench refuses.
#include <filesystem>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "csg/lower.h"
#include "experiments/csg/evaluate.h"
#include "experiments/csg/peers.h"
#include "experiments/csg/programs.h"
#include "experiments/heuristic_choice.h"
#include "io/atomic_file.h"
#include "io/obj_writer.h"
#include "validate/solid_check.h"

namespace bsp::cli {

namespace {

constexpr long long kMaxPoints = 100'000'000;

std::string_view step_name(StepKind kind) {
  switch (kind) {
    case StepKind::Union: return "union";
    case StepKind::Intersection: return "intersection";
    case StepKind::Difference: return "difference";
    case StepKind::Hull: return "hull";
    default: return "leaf";
  }
}

nlohmann::json step_json(const csg::Program& program, const experiments::CsgStepCost& s) {
  return {{"node", csg::describe(program, s.node)},
          {"op", step_name(s.kind)},
          {"operands", s.operands},
          {"merges", s.merges},
          {"seconds", s.seconds},
          {"partition_calls", s.stats.partition_calls},
          {"shp_splits", s.stats.shp_splits},
          {"merge_nodes", s.stats.merge_nodes},
          {"pruned", s.stats.pruned},
          {"compactions", s.stats.compactions},
          {"nodes_before_reduce", s.stats.before.nodes},
          {"nodes_after_reduce", s.stats.after.nodes}};
}

nlohmann::json leaf_json(const csg::Program& program, const experiments::CsgLeafCost& l) {
  return {{"node", csg::describe(program, l.node)},
          {"polygons", l.polygons},
          {"fragments", l.fragments},
          {"nodes", l.size.nodes},
          {"depth", l.size.depth},
          {"seconds", l.seconds}};
}

nlohmann::json evaluation_json(const csg::Program& program, const csg::Postfix& postfix,
                               const experiments::CsgEvaluation& e, const experiments::HeuristicChoice& heuristic,
                               const MergeOptions& merge) {
  nlohmann::json steps = nlohmann::json::array(), leaves = nlohmann::json::array();
  for (const auto& s : e.steps) steps.push_back(step_json(program, s));
  for (const auto& l : e.leaves) leaves.push_back(leaf_json(program, l));
  return {{"program", program.path},
          {"kernel", kernel_name(e.kernel)},
          {"heuristic", heuristic.name},
          {"heuristic_params", heuristic.resolved.to_json()},
          {"prune_by_bounds", merge.prune_by_bounds},
          {"leaves_built", e.leaves.size()},
          {"steps_done", e.steps.size()},
          {"lowering",
           {{"leaves", postfix.leaves.size()},
            {"ignored_wrong_dimension", postfix.stats.ignored_wrong_dimension},
            {"not_rendered", postfix.stats.not_rendered},
            {"flipped_leaves", postfix.stats.flipped_leaves},
            {"cleaned_faces", postfix.stats.cleaned_faces}}},
          {"seconds",
           {{"build", e.build_seconds},
            {"merge", e.merge_seconds},
            {"boundary", e.boundary_seconds},
            {"total", e.seconds()},
            {"input_checks", e.check_seconds}}},
          {"dropped_input", e.dropped_input},
          {"result", {{"nodes", e.result.nodes}, {"depth", e.result.depth}, {"faces", e.mesh.face_count()},
                      {"vertices", e.mesh.vertices.size()}}},
          {"check", to_json(e.check)},
          {"leaf_builds", leaves},
          {"steps", steps}};
}

// One line per step, then the totals: the merge cost of the program as it ran.
void print_text(const nlohmann::json& out) {
  for (const auto& s : out["steps"])
    std::cout << "step " << s["node"].get<std::string>() << ": " << s["op"].get<std::string>() << " of "
              << s["operands"] << ", merges " << s["merges"] << ", nodes " << s["nodes_before_reduce"] << " -> "
              << s["nodes_after_reduce"] << ", " << s["seconds"] << " s\n";
  nlohmann::json rest = out;
  rest.erase("steps");
  rest.erase("leaf_builds");
  // Exact volumes are rationals of hundreds of digits: --json prints them; text says whether equal.
  if (rest["check"].contains("volume_exact")) {
    rest["check"]["volume_equal"] = rest["check"]["volume_exact"] == rest["check"]["corefine_volume_exact"];
    rest["check"].erase("volume_exact");
    rest["check"].erase("corefine_volume_exact");
  }
  for (const auto& [k, v] : rest.items()) std::cout << k << ": " << v.dump() << "\n";
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string mesh_text(const std::string& path, const IndexedMesh& mesh, const std::string& comment) {
  if (path.ends_with(".obj")) return to_obj(mesh, comment);
  return to_off(mesh, comment);
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const std::string heuristic_name = args.option("--heuristic").value_or("octree");
  ParamAssignments params;
  for (const auto& kv : args.options("--param")) params.push_back(parse_assignment(kv));
  const auto seed = static_cast<std::uint64_t>(args.integer("--seed", 0, 9'000'000'000'000'000LL).value_or(1));
  experiments::CsgSettings settings;
  settings.check.points = static_cast<std::uint64_t>(args.integer("--points", 0, kMaxPoints).value_or(10000));
  settings.check.seed = seed;
  const auto out_path = args.option("--out");
  const std::string kernel_text = args.option("--kernel").value_or("exact");
  const std::string engine = args.option("--engine").value_or("bspbench");
  const std::string prune = args.option("--prune").value_or("off");
  std::vector<std::string> peers;
  if (const auto list = args.option("--peers")) peers = split_list(*list);
  const double timeout = args.real("--peer-timeout").value_or(experiments::kDefaultPeerTimeout);
  const std::vector<std::string> files = args.positional();
  args.finish();
  if (files.size() != 1) throw UsageError("csg takes one program: FILE.csg, openscad:NAME or NAME:k=K");
  if (!(timeout > 0)) throw UsageError("--peer-timeout must be a positive number of seconds");
  const auto kernel = kernel_named(kernel_text);
  if (!kernel) throw UsageError("--kernel must be exact or float, not '" + kernel_text + "'");
  settings.kernel = *kernel;
  if (prune != "on" && prune != "off") throw UsageError("--prune must be on or off, not '" + prune + "'");
  settings.merge.prune_by_bounds = prune == "on";
  if (out_path && !out_path->ends_with(".obj") && !out_path->ends_with(".off"))
    throw UsageError("--out must name a .obj or .off file, not '" + *out_path + "'");

  const auto heuristic = experiments::HeuristicChoice::of(heuristic_name, params);
  const experiments::ProgramSource source = experiments::parse_program_source(files[0]);
  for (const std::string& peer : peers)
    if (!experiments::is_peer(peer)) throw UsageError("--peers takes cgal, openscad and manifold, not '" + peer + "'");
  if (engine != "bspbench" && engine != "cgal")
    throw UsageError("--engine runs bspbench or cgal here; openscad and manifold run through --peers");
  if (engine == "cgal" && (!peers.empty() || out_path)) throw UsageError("--engine cgal takes neither --peers nor --out");
  // A scratch folder only where a file is written: a generated or exported program, or a peer's files
  // (the CGAL child, which a timeout may kill, writes none for a program file).
  const bool scratch_needed = source.generated() || source.name.rfind("openscad:", 0) == 0 || !peers.empty();
  const auto scratch = scratch_needed ? experiments::scratch_folder("cli") : std::filesystem::path();
  struct Cleanup {
    std::filesystem::path dir;
    ~Cleanup() {
      if (!dir.empty()) std::filesystem::remove_all(dir);
    }
  } cleanup{scratch};
  const experiments::LoadedProgram loaded = experiments::load_program(source, seed, scratch);
  if (engine == "cgal") {
    // One peer alone, in this process: how the csg runs time CGAL in a child they can stop.
    std::cout << to_json(experiments::run_cgal(loaded.postfix)).dump() << "\n";
    return 0;
  }
  const auto splitter = heuristic.splitter(seed);
  const experiments::CsgEvaluation e = experiments::evaluate_program(loaded.program, loaded.postfix, *splitter, settings);
  nlohmann::json out = evaluation_json(loaded.program, loaded.postfix, e, heuristic, settings.merge);
  out["program"] = source.label();
  for (const std::string& peer : peers)
    out["peers"][peer] = to_json(experiments::run_peer(peer, loaded.file, loaded.postfix, scratch,
                                                       {timeout, experiments::self_executable()}));
  if (out_path)
    write_file_atomically(*out_path, mesh_text(*out_path, e.mesh, "bspbench csg " + source.label() + " (" + heuristic.label + ", " +
                                                                     kernel_name(e.kernel) + " kernel)"));
  if (json) std::cout << out.dump() << "\n";
  else print_text(out);
  return e.check.ok() ? 0 : 1;
}

}  // namespace

Command csg_command() {
  return {"csg",
          "FILE.csg|openscad:NAME|NAME:k=K [--heuristic H] [--param k=v]... [--seed S] [--kernel exact|float] [--prune on|off] "
          "[--points N] [--peers cgal,openscad,manifold] [--peer-timeout SECONDS] [--engine bspbench|cgal] [--out RESULT.obj|.off] [--json]",
          "evaluate an OpenSCAD CSG program by merging solid BSP trees, proved against CGAL step by step", run,
          concat({{{"FILE.csg", "a program in OpenSCAD's CSG format (openscad -o FILE.csg MODEL.scad)"},
                   {"openscad:NAME", "an example model OpenSCAD ships (/usr/share/openscad/examples), exported by openscad"},
                   {"NAME:k=K", "a generated program: drilled-plate (a plate minus K holes) or sphere-union (K spheres), from the seed"},
                   {"--peers LIST", "also run these engines on the same program: cgal (corefinement step by step), openscad (its render of the file), manifold (manifold-3d under node)"},
                   {"--peer-timeout S", "seconds before a peer is killed and recorded as timed out (default 600)"},
                   {"--engine E", "bspbench (default), or cgal alone: CGAL's corefinement step by step, one JSON line (what --peers cgal runs in a child)"},
                   {"--heuristic H", "heuristic that builds every leaf's solid tree (default octree)"},
                   {"--param k=v", "a heuristic parameter; repeatable"},
                   {"--seed S", "the heuristic's seed and the check's points' (default 1)"},
                   {"--kernel K", "exact (default: every leaf snapped to one grid, merged exactly, volumes equal as rationals) or float"},
                   {"--prune on|off", "merging passes a subtree whose bounds lie on one side of a plane whole (default off: it visits the same nodes, docs/solids.md)"},
                   {"--points N", "points classified against the program's exact answer (default 10000)"},
                   {"--out RESULT", "write the result's boundary, welded, as .obj or .off (atomically)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
