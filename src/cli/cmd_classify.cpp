// bspbench classify: point membership as a tree query [Thibault1987]: a closed solid becomes a
// solid tree, and each point of a file is IN, OUT or ON (within plane_eps of the boundary). With
// --kernel exact the solid and the points are snapped to the grid of the solid's box and each
// snapped point is decided exactly (ON: exactly on the snapped boundary); a point beyond the grid's
// range lies outside the box, so OUT.
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/run_args.h"
#include "common/errors.h"
#include "solid/boundary.h"
#include "solid/exact_solid_tree.h"
#include "solid/solid_build.h"
#include "experiments/heuristic_choice.h"
#include "validate/exact_solid_check.h"

namespace bsp::cli {

namespace {

// One point per line as three numbers; blank lines and lines starting with '#' are skipped.
std::vector<Vec3> read_points(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the points file");
  std::vector<Vec3> points;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    Vec3 p;
    std::string extra;
    if (!(fields >> p.x >> p.y >> p.z) || (fields >> extra) || !is_finite(p))
      throw InputError(path + ": line " + std::to_string(number) + ": expected three finite numbers");
    points.push_back(p);
  }
  return points;
}

int run(Args& args) {
  const bool json = args.flag("--json");
  const std::string spec = args.required("--solid");
  const auto params = args.options("--solid-param");
  const std::string points_path = args.required("--points");
  const std::string heuristic = args.option("--heuristic").value_or("halving");
  ParamAssignments hparams;
  for (const auto& kv : args.options("--param")) hparams.push_back(parse_assignment(kv));
  const std::string kernel_text = args.option("--kernel").value_or("float");
  args.finish();
  const auto kernel = kernel_named(kernel_text);
  if (!kernel) throw UsageError("--kernel must be float or exact, not '" + kernel_text + "'");
  const Scene scene = scene_or_file(spec, params, "--solid-param");
  const std::vector<Vec3> points = read_points(points_path);
  const Box box = solid_box(bounds(scene), bounds(scene));
  require_closed_solid(scene.polygons, Tolerance::for_extent(box.diagonal()).plane_eps, scene.name);
  auto splitter = experiments::per_node_splitter(heuristic, hparams, 1);
  std::vector<PointClass> answers;
  answers.reserve(points.size());
  if (*kernel == Kernel::Exact) {
    const auto space = ExactSolidSpace::for_box(box);
    require_snapped_solid(scene.polygons, space->grid(), scene.name);
    const ExactSolidTree solid = build_exact_solid(scene.polygons, *splitter, *space).solid;
    for (const Vec3& p : points) {
      const auto q = space->grid().snap(p);
      answers.push_back(q ? classify_point(solid, *space, *q) : PointClass::Out);
    }
  } else {
    const SolidTree solid = build_solid(scene.polygons, *splitter, box).solid;
    for (const Vec3& p : points) answers.push_back(classify_point(solid, p));
  }
  const char* names[] = {"out", "in", "on"};
  std::uint64_t counts[3] = {0, 0, 0};
  std::vector<std::string> classes;
  std::string text;
  for (const PointClass answer : answers) {
    const auto c = static_cast<int>(answer);
    ++counts[c];
    if (json) classes.push_back(names[c]);
    else text += std::string(names[c]) + "\n";
  }
  if (json) {
    nlohmann::json out{{"solid", scene.name}, {"heuristic", heuristic},   {"points", points.size()},
                       {"in", counts[1]},      {"out", counts[0]},           {"on", counts[2]},
                       {"classes", classes}};
    if (*kernel != Kernel::Float) out["kernel"] = kernel_name(*kernel);
    std::cout << out.dump() << "\n";
  } else {
    std::cout << text;
  }
  return 0;
}

}  // namespace

Command classify_command() {
  return {"classify", "--solid SCENE|FILE [--solid-param k=v]... --points FILE [--heuristic H] [--param k=v]... [--kernel float|exact] [--json]",
          "classify points as IN, OUT or ON a closed solid with its solid BSP tree", run,
          concat({{{"--solid SCENE|FILE", "a closed solid scene (bspbench scenes), mesh:NAME, or a mesh file"},
                   {"--solid-param k=v", "a parameter of the solid's scene; repeatable"},
                   {"--points FILE", "one point per line as x y z; '#' starts a comment line"},
                   {"--heuristic H", "heuristic that builds the solid tree (default halving)"},
                   {"--param k=v", "a heuristic parameter; repeatable"},
                   {"--kernel K", "float (default: ON within plane_eps) or exact (solid and points snapped to the grid, decided exactly)"}},
                  kJsonOption})};
}

}  // namespace bsp::cli
