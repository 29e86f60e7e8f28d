#pragma once
// The scene catalog: every generator by name, with its parameters and what it is for. Generators
// are deterministic: the same name, parameters and seed give byte-identical polygons on every
// machine and thread count (each item draws from its own stream, rng.h stream_seed).
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"
#include "scene/scene.h"

namespace bsp {

struct GeneratorInfo {
  std::string name;
  std::string purpose;     // one line: what a user learns from this scene
  std::string count_rule;  // exactly how the parameters map to the polygon count
  std::vector<ParamSpec> params;
  std::function<std::vector<Polygon>(const ParamSet&)> make;
  // Whether the scene keeps its density as n grows (more of the same neighbourhood, as a larger
  // level or a finer grid), so growth against n measures the heuristic; false where each polygon
  // meets more others as n grows (random-triangles at a fixed size, the lower-bound constructions).
  bool constant_density = false;
  // Whether the surface is closed and faces outwards, so it can become a solid tree (solids.cpp).
  bool closed_solid = false;
  // Whether the scene is 2D: segments at z = 0 (geometry/segment2.h). Suite blocks and benchmarks
  // that name no scenes run only 3D ones; 2D scenes are measured where a block names them.
  bool segments = false;
};

const std::vector<GeneratorInfo>& generators();
// Throws UsageError naming the known scenes.
const GeneratorInfo& find_generator(std::string_view name);
// Also loads "mesh:NAME" scenes (mesh_scenes.h). Throws UsageError for an unknown scene, parameter
// or value.
Scene make_scene(std::string_view name, const ParamAssignments& params);

// Shared parameter specs.
ParamSpec n_param(double default_n, std::string doc);
ParamSpec seed_param();

// One declaration per generator file.
GeneratorInfo random_triangles_generator();
GeneratorInfo cyclic_overlap_generator();
GeneratorInfo random_disjoint_generator();
GeneratorInfo random_segments_generator();
GeneratorInfo doom_piece_generator();
GeneratorInfo architecture_generator();
GeneratorInfo city_generator();
GeneratorInfo terrain_generator();
GeneratorInfo sphere_field_generator();
GeneratorInfo saddle_grid_generator();
GeneratorInfo orthogonal_stacks_generator();
GeneratorInfo coplanar_heavy_generator();
GeneratorInfo near_degenerate_generator();
std::vector<GeneratorInfo> solid_generators();

}  // namespace bsp
