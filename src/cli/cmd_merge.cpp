// bspbench merge: two closed solids as solid trees built by one heuristic, merged by a set
// operation [Naylor1990], the result proved against CGAL (validate/solid_check.h), its merge cost
// printed, and its boundary optionally written as OBJ. Exit code 1 when the proof fails.
#include <iostream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "experiments/heuristic_choice.h"
#include "experiments/merge/set_operation.h"
#include "io/atomic_file.h"
#include "io/obj_writer.h"

namespace bsp::cli {

namespace {

constexpr long long kMaxPoints = 100'000'000;

// "X,Y,Z" as a vector; throws UsageError naming the option.
Vec3 parse_offset(const std::string& text, std::string_view option) {
  Vec3 v;
  char comma1 = 0, comma2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' || !in.eof() || !is_finite(v))
    throw UsageError(std::string(option) + " takes X,Y,Z (three finite numbers), not '" + text + "'");
  return v;
}

// The operand's scene or file, moved by `offset`.
Scene operand(const std::string& spec, const std::vector<std::string>& params, std::string_view which,
              const std::optional<std::string>& offset) {
  Scene scene = scene_or_file(spec, params, std::string(which) + "-param");
  if (offset) {
    const Vec3 d = parse_offset(*offset, std::string(which) + "-offset");
    for (Polygon& p : scene.polygons)
      for (Vertex& v : p.verts) v.p += d;
    check_scene(scene, scene.name);
  }
  return scene;
}

nlohmann::json operand_json(const Scene& scene, const SolidBuild& b) {
  const SolidSize size = solid_size(b.solid);
  return {{"scene", scene_json(scene)},
          {"fragments", b.fragments},
          // Faces or parts narrower than plane_eps that the build dropped: the tree's solid lacks them.
          {"dropped_input", b.build.dropped_input},
          {"dropped_slivers", b.build.dropped_slivers},
          {"dropped_area", b.build.dropped_area},
          {"build_seconds", b.build.build_seconds},
          {"label_seconds", b.label_seconds},
          {"nodes", size.nodes},
          {"depth", size.depth},
          {"in_leaves", size.in_leaves},
          {"out_leaves", size.out_leaves}};
}

nlohmann::json exact_operand_json(const Scene& scene, const ExactSolidBuild& b) {
  const SolidSize size = solid_size(b.solid);
  return {{"scene", scene_json(scene)},
          {"fragments", b.fragments},
          {"dropped_input", b.build.dropped_input},  // snapping collapsed them (exact_build.h)
          {"build_seconds", b.build.build_seconds},
          {"label_seconds", b.label_seconds},
          {"nodes", size.nodes},
          {"depth", size.depth},
          {"in_leaves", size.in_leaves},
          {"out_leaves", size.out_leaves}};
}

void print(const nlohmann::json& out, bool json) {
  if (json) {
    std::cout << out.dump() << "\n";
  } else {
    for (const auto& [k, v] : out.items()) std::cout << k << ": " << v.dump() << "\n";
  }
}

// The exact kernel's merge (experiments/merge/set_operation.h). The OBJ's vertices are computed from
// their planes and rounded; the faces that share a vertex exactly are welded within plane_eps for
// the file, which is output only.
int run_exact(const Scene& a, const Scene& b, SetOp op, const experiments::HeuristicChoice& heuristic,
              std::uint64_t seed, const SolidCheckSettings& settings, const std::optional<std::string>& out_path,
              bool json) {
  const auto splitter = heuristic.splitter(seed);
  const experiments::ExactSetOperationRun run = experiments::run_exact_set_operation(a, b, op, *splitter, settings);
  const nlohmann::json out = {{"op", set_op_name(op)},
                              {"kernel", "exact"},
                              {"heuristic", heuristic.name},
                              {"heuristic_params", heuristic.resolved.to_json()},
                              {"seed", seed},
                              {"a", exact_operand_json(a, run.operands.a)},
                              {"b", exact_operand_json(b, run.operands.b)},
                              {"merge", to_json(run.stats)},
                              {"check", to_json(run.check)}};
  if (out_path) {
    LoopPool faces;
    for (const PlanePolygon& f : run.boundary) faces.add(vertex_positions(f, run.operands.space->grid()));
    IndexedMesh mesh;
    const Box box = solid_box(bounds(a), bounds(b));
    check_boundary(faces, Tolerance::for_extent(box.diagonal()).plane_eps, &mesh);
    write_file_atomically(*out_path, to_obj(mesh, "bspbench merge --kernel exact " + std::string(set_op_name(op)) +
                                                      " of " + a.name + " and " + b.name + " (" + heuristic.name + ")"));
  }
  print(out, json);
  return run.check.ok() ? 0 : 1;
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const std::string a_spec = args.required("--a"), b_spec = args.required("--b");
  const auto a_params = args.options("--a-param"), b_params = args.options("--b-param");
  const auto a_offset = args.option("--a-offset"), b_offset = args.option("--b-offset");
  const SetOp op = parse_set_op(args.required("--op"));
  const std::string heuristic_name = args.option("--heuristic").value_or("naylor");
  ParamAssignments params;
  for (const auto& kv : args.options("--param")) params.push_back(parse_assignment(kv));
  const auto seed = static_cast<std::uint64_t>(args.integer("--seed", 0, 9'000'000'000'000'000LL).value_or(1));
  SolidCheckSettings settings;
  settings.points = static_cast<std::uint64_t>(args.integer("--points", 0, kMaxPoints).value_or(settings.points));
  settings.seed = seed;
  const auto out_path = args.option("--out");
  const std::string kernel_text = args.option("--kernel").value_or("float");
  args.finish();
  const auto kernel = kernel_named(kernel_text);
  if (!kernel) throw UsageError("--kernel must be float or exact, not '" + kernel_text + "'");
  if (out_path && !out_path->ends_with(".obj")) throw UsageError("--out must name a .obj file, not '" + *out_path + "'");

  const Scene a = operand(a_spec, a_params, "--a", a_offset), b = operand(b_spec, b_params, "--b", b_offset);
  const auto heuristic = experiments::HeuristicChoice::of(heuristic_name, params);
  if (*kernel == Kernel::Exact) return run_exact(a, b, op, heuristic, seed, settings, out_path, json);
  const auto splitter = heuristic.splitter(seed);
  const experiments::SetOperationRun run = experiments::run_set_operation(a, b, op, *splitter, settings);
  const SolidTree& result = run.result;
  const SolidCheck& check = run.check;

  nlohmann::json out = {{"op", set_op_name(op)},
                        {"heuristic", heuristic.name},
                        {"heuristic_params", heuristic.resolved.to_json()},
                        {"seed", seed},
                        {"a", operand_json(a, run.operands.a)},
                        {"b", operand_json(b, run.operands.b)},
                        {"merge", to_json(run.stats)},
                        {"check", to_json(check)}};
  if (out_path) {
    IndexedMesh mesh;
    check_boundary(solid_boundary(result), result.tol.plane_eps, &mesh);
    write_file_atomically(*out_path, to_obj(mesh, "bspbench merge " + std::string(set_op_name(op)) + " of " + a.name +
                                                      " and " + b.name + " (" + heuristic.name + ")"));
  }
  print(out, json);
  return check.ok(kVolumeRelativeTolerance) ? 0 : 1;
}

}  // namespace

Command merge_command() {
  return {"merge",
          "--a SCENE|FILE [--a-param k=v]... [--a-offset X,Y,Z] --b SCENE|FILE [--b-param k=v]... [--b-offset X,Y,Z] --op union|intersection|difference|xor "
          "[--heuristic H] [--param k=v]... [--seed S] [--points N] [--kernel float|exact] [--out RESULT.obj] [--json]",
          "set operation on two closed solids by merging their BSP trees, proved against CGAL", run,
          concat({{{"--a SCENE|FILE", "first operand: a closed solid scene (bspbench scenes), mesh:NAME, or a mesh file"},
                   {"--a-param k=v", "a parameter of the first operand's scene (x, y, z, scale, n, seed...); repeatable"},
                   {"--a-offset X,Y,Z", "move the first operand by this vector (meshes and files have no placement parameters)"},
                   {"--b SCENE|FILE", "second operand, as --a"},
                   {"--b-param k=v", "a parameter of the second operand's scene; repeatable"},
                   {"--b-offset X,Y,Z", "move the second operand by this vector"},
                   {"--op OP", "union, intersection, difference (a - b) or xor"},
                   {"--heuristic H", "heuristic that builds both operands' trees (default naylor)"},
                   {"--param k=v", "a heuristic parameter; repeatable"},
                   {"--seed S", "the heuristic's seed and the check's points' (default 1)"},
                   {"--points N", "points classified against CGAL's exact answer (default 100000)"},
                   {"--kernel K", "float (default) or exact: the operands snapped to one grid, merged exactly, the result's exact volume against CGAL's exact corefinement"},
                   {"--out RESULT.obj", "write the result's boundary, welded, as OBJ (atomically)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
