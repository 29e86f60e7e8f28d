#pragma once
// A scene: the polygons a build starts from, with where they came from. Generated scenes come from
// generators/catalog.h, file scenes from io/mesh_reader.h; both end up here.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "geometry/polygon.h"

namespace bsp {

// What loading a file changed (zero for generated scenes).
struct SceneLoadStats {
  std::uint64_t faces_read = 0;
  std::uint64_t triangulated = 0;      // non-convex or non-planar faces replaced by triangles
  std::uint64_t dropped_degenerate = 0;  // zero-area faces
  std::uint64_t dropped_duplicate_vertex = 0;  // faces repeating a vertex (by index or position)
};

struct Scene {
  std::string name;  // catalog name, or "file:PATH"
  ParamSet params;   // resolved generator parameters; empty for files
  std::vector<Polygon> polygons;
  SceneLoadStats load;
};

Box bounds(const Scene& scene);
// Stable across machines: FNV-1a over every vertex's coordinates and texture coordinates in order.
std::string content_hash(const Scene& scene);
// {name, params, n_polygons, hash, bounds: {lo, hi}, load stats for files}
nlohmann::json scene_json(const Scene& scene);
// Throws InputError naming `origin` for an empty scene or a non-finite coordinate.
void check_scene(const Scene& scene, std::string_view origin);

}  // namespace bsp
