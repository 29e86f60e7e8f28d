#include "scene/scene.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/hash.h"

namespace bsp {

Box bounds(const Scene& scene) {
  Box b;
  for (const auto& p : scene.polygons)
    for (const auto& v : p.verts) b.add(v.p);
  return b;
}

std::string content_hash(const Scene& scene) {
  Hasher h;
  h.add_u64(scene.polygons.size());
  for (const auto& p : scene.polygons) {
    h.add_u64(p.verts.size());
    for (const auto& v : p.verts) {
      h.add_double(v.p.x);
      h.add_double(v.p.y);
      h.add_double(v.p.z);
      h.add_double(v.u);
      h.add_double(v.v);
    }
  }
  return h.hex();
}

nlohmann::json scene_json(const Scene& scene) {
  const Box b = bounds(scene);
  nlohmann::json j{{"name", scene.name},
                   {"params", scene.params.to_json()},
                   {"n_polygons", scene.polygons.size()},
                   {"hash", content_hash(scene)},
                   {"bounds", {{"lo", {b.lo.x, b.lo.y, b.lo.z}}, {"hi", {b.hi.x, b.hi.y, b.hi.z}}}}};
  if (scene.load.faces_read > 0)
    j["load"] = {{"faces_read", scene.load.faces_read},
                 {"triangulated", scene.load.triangulated},
                 {"dropped_degenerate", scene.load.dropped_degenerate},
                 {"dropped_duplicate_vertex", scene.load.dropped_duplicate_vertex}};
  return j;
}

void check_scene(const Scene& scene, std::string_view origin) {
  if (scene.polygons.empty()) throw InputError(std::string(origin) + ": the scene has no polygons");
  for (std::size_t i = 0; i < scene.polygons.size(); ++i)
    for (const auto& v : scene.polygons[i].verts) {
      if (!is_finite(v.p) || !std::isfinite(v.u) || !std::isfinite(v.v))
        throw InputError(std::string(origin) + ": polygon " + std::to_string(i) +
                         " has a non-finite (NaN or infinite) coordinate");
      // Trees store texture coordinates as floats.
      if (std::abs(v.u) > std::numeric_limits<float>::max() || std::abs(v.v) > std::numeric_limits<float>::max())
        throw InputError(std::string(origin) + ": polygon " + std::to_string(i) +
                         " has a texture coordinate beyond the float range");
    }
}

}  // namespace bsp
