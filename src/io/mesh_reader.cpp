#include "io/mesh_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/errors.h"
#include "geometry/tolerance.h"
#include "io/mesh_claims.h"
#include "io/mesh_reader_cgal.h"
#include "io/polygon_cleanup.h"

namespace bsp {

namespace {

std::string extension_of(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

void check_readable(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw InputError(path + ": unsupported file type '" + ext + "' (expected .obj, .off, .ply or .stl)");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory");
}

// The whole file, read once for check_mesh_claims before CGAL reads it again.
std::string read_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::ostringstream s;
  s << in.rdbuf();
  std::string content = std::move(s).str();
  if (content.empty()) throw InputError(path + ": the file is empty");
  return content;
}

Box soup_bounds(const std::string& path, const PolygonSoup& soup) {
  Box b;
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const Vec3 p{soup.points[i][0], soup.points[i][1], soup.points[i][2]};
    if (!is_finite(p))
      throw InputError(path + ": vertex " + std::to_string(i) + " has a non-finite (NaN or infinite) coordinate");
    b.add(p);
  }
  return b;
}

// CGAL rejects a text mesh without saying why; name the two usual reasons, a non-finite number
// (nan, inf, or one like 1e400 that overflows) and an OBJ without faces. Empty when neither.
std::string diagnose_rejected_text_mesh(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  bool obj_face = false;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() + token.size() && !std::isfinite(value))
        return "line " + std::to_string(number) + " has a non-finite (NaN or infinite) coordinate '" + token + "'";
    }
    obj_face |= line.rfind("f ", 0) == 0;
  }
  if (extension_of(path) == ".obj" && !obj_face) return "the file has no faces";
  return {};
}

}  // namespace

Scene read_mesh(const std::string& path) {
  check_readable(path);
  const std::string content = read_contents(path);
  check_mesh_claims(path, content, extension_of(path));
  PolygonSoup soup;
  std::string error;
  const bool obj = extension_of(path) == ".obj";
  if (!read_polygon_soup_cgal(path, soup, error)) {
    const std::string reason = diagnose_rejected_text_mesh(path);
    if (reason.empty() && obj) check_obj_face_indices(path, content);
    throw InputError(path + ": " + (reason.empty() ? "malformed mesh (" + error + ")" : reason));
  }
  if (obj) check_obj_face_indices(path, content);
  const Tolerance tol = Tolerance::for_extent(soup_bounds(path, soup).diagonal());
  Scene scene;
  scene.name = "file:" + path;
  scene.load.faces_read = soup.faces.size();
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    Polygon poly;
    for (auto index : face) {
      if (index >= soup.points.size())
        throw InputError(path + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                         " but the file has " + std::to_string(soup.points.size()));
      const auto& p = soup.points[index];
      poly.verts.push_back({{p[0], p[1], p[2]}, 0, 0});
    }
    if (std::set<std::size_t>(face.begin(), face.end()).size() != face.size()) {
      ++scene.load.dropped_duplicate_vertex;
      continue;
    }
    append_clean_polygon(std::move(poly), tol.plane_eps, scene.polygons, scene.load);
  }
  for (std::uint32_t i = 0; i < scene.polygons.size(); ++i) scene.polygons[i].source = i;
  check_scene(scene, path);
  return scene;
}

}  // namespace bsp
