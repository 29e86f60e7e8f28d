#include "io/polygon_cleanup.h"

#include <cmath>

namespace bsp {

bool is_convex_planar(const Polygon& poly, double eps) {
  const auto plane = supporting_plane(poly);
  if (!plane) return false;
  const auto& v = poly.verts;
  const std::size_t k = v.size();
  for (const auto& x : v)
    if (std::abs(plane->distance(x.p)) > eps) return false;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 turn = cross(v[(i + 1) % k].p - v[i].p, v[(i + 2) % k].p - v[(i + 1) % k].p);
    if (dot(turn, plane->n) < -eps * length(v[(i + 1) % k].p - v[i].p)) return false;
  }
  return true;
}

void append_clean_polygon(Polygon&& poly, double eps, std::vector<Polygon>& out, SceneLoadStats& stats) {
  if (poly.verts.size() < 3 || !(area(poly) > 0.0)) {
    ++stats.dropped_degenerate;
    return;
  }
  if (is_convex_planar(poly, eps)) {
    out.push_back(std::move(poly));
    return;
  }
  ++stats.triangulated;
  for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i) {
    Polygon t{{poly.verts[0], poly.verts[i], poly.verts[i + 1]}, poly.source};
    if (area(t) > 0.0) out.push_back(std::move(t));
  }
}

}  // namespace bsp
