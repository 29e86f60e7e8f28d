// bspbench heuristics / scenes: what the registries hold, with parameters and defaults.
#include <iostream>
#include <nlohmann/json.hpp>

#include "catalog.h"
#include "common/errors.h"
#include "io/mesh_reader.h"
#include "solid/boundary.h"
#include "cli/commands.h"
#include "mesh_scenes.h"
#include "experiments/heuristic_choice.h"
#include "search/tree_search.h"
#include "split/registry.h"

namespace bsp::cli {

namespace {

void print(const nlohmann::json& list, bool json) {
  if (json) {
    std::cout << list.dump(2) << "\n";
    return;
  }
  for (const auto& item : list) {
    std::cout << item["name"].get<std::string>() << ": " << item["summary"].get<std::string>() << "\n";
    if (item.contains("closed_solid"))
      std::cout << "    solid: "
                << (item["closed_solid"].get<bool>() ? "closed, an operand for bspbench merge"
                                                     : "no" + (item.contains("not_solid_because")
                                                                   ? " (" + item["not_solid_because"].get<std::string>() + ")"
                                                                   : std::string()))
                << "\n";
    if (item.contains("constant_density"))
      std::cout << "    density: " << (item["constant_density"].get<bool>() ? "constant as n grows" : "grows with n")
                << "\n";
    for (const auto& p : item["params"])
      std::cout << "    " << p["name"].get<std::string>() << " = " << p["default"].dump() << "  "
                << p["doc"].get<std::string>() << "\n";
  }
}

int run_heuristics(Args& args) {
  const bool json = args.flag("--json");
  args.finish();
  nlohmann::json list = nlohmann::json::array();
  for (const auto& h : heuristics())
    list.push_back({{"name", h.name}, {"summary", h.summary}, {"autopartition", h.autopartition},
                    {"params", specs_to_json(h.params)}});
  // Searching builders take the same names and parameters wherever a tree is built from a name; one
  // is an autopartition when its base is (listed for its default base).
  for (const auto& s : searches())
    list.push_back({{"name", s.name}, {"summary", "search: " + s.summary},
                    {"autopartition", experiments::HeuristicChoice::of(s.name, {}).autopartition()},
                    {"params", specs_to_json(s.params)}});
  print(list, json);
  return 0;
}

int run_scenes(Args& args) {
  const bool json = args.flag("--json");
  args.finish();
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : generators())
    list.push_back({{"name", g.name}, {"kind", "generator"}, {"summary", g.purpose}, {"count", g.count_rule},
                    {"constant_density", g.constant_density}, {"closed_solid", g.closed_solid},
                    {"params", specs_to_json(g.params)}});
  for (const auto& m : available_meshes()) {
    nlohmann::json item = {{"name", std::string(kMeshPrefix) + m.name}, {"kind", "mesh"}, {"path", m.path},
                           {"summary", "real mesh read from " + m.path},
                           {"count", "the file's faces: convex planar ones kept, others triangulated, degenerate ones dropped"},
                           {"params", nlohmann::json::array()}};
    // Whether bspbench merge takes it: the same check, on the mesh as loaded.
    try {
      const Scene scene = read_mesh(m.path);
      require_closed_solid(scene.polygons, Tolerance::for_extent(bounds(scene).diagonal()).plane_eps, m.path);
      item["closed_solid"] = true;
    } catch (const InputError& e) {
      item["closed_solid"] = false;
      const std::string why = e.what();
      item["not_solid_because"] = why.substr(why.find(": ") == std::string::npos ? 0 : why.find(": ") + 2);
    }
    list.push_back(std::move(item));
  }
  print(list, json);
  return 0;
}

}  // namespace

Command heuristics_command() {
  return {"heuristics", "[--json]", "list the splitter heuristics with their parameters", run_heuristics,
          {{"--json", "print the list as JSON"}}};
}

Command scenes_command() {
  return {"scenes", "[--json]", "list the scene generators with their parameters, and the fetched mesh:NAME scenes (each read, to say whether it is a closed solid)",
          run_scenes, {{"--json", "print the list as JSON"}}};
}

}  // namespace bsp::cli
