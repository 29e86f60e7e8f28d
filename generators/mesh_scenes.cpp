#include "mesh_scenes.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "common/errors.h"
#include "io/mesh_reader.h"

namespace bsp {

namespace {

// File types read_mesh understands, in the order that decides which file keeps the bare stem.
constexpr std::string_view kExtensions[] = {".off", ".obj", ".ply", ".stl"};

int extension_rank(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  for (int i = 0; i < 4; ++i)
    if (ext == kExtensions[i]) return i;
  return -1;
}

}  // namespace

bool is_mesh_scene(std::string_view scene_name) { return scene_name.starts_with(kMeshPrefix); }

std::string mesh_cache_dir() {
  if (const char* dir = std::getenv("BSPBENCH_MESH_DIR"); dir && *dir) return dir;
  return BSPBENCH_MESH_CACHE;
}

std::vector<MeshEntry> available_meshes() {
  std::error_code ec;
  std::map<std::pair<std::string, int>, std::string> files;  // (stem, extension rank) -> path
  for (const auto& entry : std::filesystem::directory_iterator(mesh_cache_dir(), ec)) {
    const int rank = extension_rank(entry.path());
    if (rank >= 0 && entry.is_regular_file(ec)) files[{entry.path().stem().string(), rank}] = entry.path().string();
  }
  std::vector<MeshEntry> out;
  std::string previous_stem;
  for (const auto& [key, path] : files) {
    const bool repeated = !out.empty() && key.first == previous_stem;
    out.push_back({repeated ? std::filesystem::path(path).filename().string() : key.first, path});
    previous_stem = key.first;
  }
  std::sort(out.begin(), out.end(), [](const MeshEntry& a, const MeshEntry& b) { return a.name < b.name; });
  return out;
}

std::string mesh_scene_path(std::string_view scene_name) {
  const std::string_view name = scene_name.substr(kMeshPrefix.size());
  const auto meshes = available_meshes();
  const auto it = std::find_if(meshes.begin(), meshes.end(), [&](const MeshEntry& m) { return m.name == name; });
  if (it == meshes.end())
    throw UsageError("unknown mesh scene '" + std::string(scene_name) + "': no such mesh in " + mesh_cache_dir() +
                     (meshes.empty() ? " (empty: run generators/fetch_meshes.sh)" : " (bspbench scenes lists them)"));
  return it->path;
}

Scene load_mesh_scene(std::string_view scene_name, const ParamAssignments& params) {
  if (!params.empty())
    throw UsageError("scene " + std::string(scene_name) + ": unknown parameter '" + params.front().first +
                     "' (mesh scenes take no parameters)");
  Scene scene = read_mesh(mesh_scene_path(scene_name));
  scene.name = std::string(scene_name);
  return scene;
}

}  // namespace bsp
