#pragma once
// Real meshes as scenes: "mesh:NAME" is the file NAME.{off,obj,ply,stl} in the mesh cache, which
// generators/fetch_meshes.sh fills with the CGAL sample meshes (Debian package libcgal-demo). The
// cache is looked up at run time, so the catalog lists whatever has been fetched.
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"
#include "scene/scene.h"

namespace bsp {

inline constexpr std::string_view kMeshPrefix = "mesh:";

struct MeshEntry {
  std::string name;  // without the prefix: the file name without extension, or with it when two
                     // files share a stem (sphere.off is "sphere", sphere.ply "sphere.ply")
  std::string path;
};

bool is_mesh_scene(std::string_view scene_name);
// $BSPBENCH_MESH_DIR when set, else the repository's .cache/meshes.
std::string mesh_cache_dir();
// The meshes in the cache, sorted by name; empty when nothing has been fetched.
std::vector<MeshEntry> available_meshes();
// The file of "mesh:NAME" in the cache. Throws UsageError for a name not in the cache (saying how to
// fetch the meshes).
std::string mesh_scene_path(std::string_view scene_name);
// Loads "mesh:NAME" through read_mesh; the scene keeps that name. Mesh scenes take no parameters.
// Throws UsageError for a parameter or a name not in the cache (saying how to fetch the meshes).
Scene load_mesh_scene(std::string_view scene_name, const ParamAssignments& params);

}  // namespace bsp
