#include "catalog.h"

#include "common/errors.h"
#include "mesh_scenes.h"

namespace bsp {

const std::vector<GeneratorInfo>& generators() {
  static const std::vector<GeneratorInfo> all = [] {
    std::vector<GeneratorInfo> list = {
      random_triangles_generator(),
      cyclic_overlap_generator(),
      random_disjoint_generator(),
      random_segments_generator(),
      doom_piece_generator(),
      architecture_generator(),
      city_generator(),
      terrain_generator(),
      sphere_field_generator(),
      saddle_grid_generator(),
      orthogonal_stacks_generator(),
      coplanar_heavy_generator(),
      near_degenerate_generator(),
    };
    for (GeneratorInfo& g : solid_generators()) list.push_back(std::move(g));
    return list;
  }();
  return all;
}

const GeneratorInfo& find_generator(std::string_view name) {
  for (const auto& g : generators())
    if (g.name == name) return g;
  std::string known;
  for (const auto& g : generators()) known += (known.empty() ? "" : ", ") + g.name;
  throw UsageError("unknown scene '" + std::string(name) + "' (known: " + known + ")");
}

Scene make_scene(std::string_view name, const ParamAssignments& params) {
  if (is_mesh_scene(name)) return load_mesh_scene(name, params);
  const GeneratorInfo& g = find_generator(name);
  Scene scene;
  scene.name = g.name;
  scene.params = ParamSet::resolve(g.params, params, "scene " + g.name);
  scene.polygons = g.make(scene.params);
  return scene;
}

ParamSpec n_param(double default_n, std::string doc) {
  return {"n", ParamSpec::Kind::Integer, std::move(doc), default_n, 1, 1e8, {}};
}

ParamSpec seed_param() {
  return {"seed", ParamSpec::Kind::Integer, "random seed; the same seed gives the same polygons", 1, 0, 9e15, {}};
}

}  // namespace bsp
