#pragma once
// Our polygons as a CGAL surface mesh, for the CGAL translation units only (exact_solid.cpp,
// exact_nef.cpp, exact_measure.cpp): convex faces fanned into triangles, vertices shared by exact
// coordinates; and CGAL's exact numbers as GMP rationals.
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <gmpxx.h>

#include <map>
#include <span>
#include <tuple>
#include <type_traits>
#include <vector>

#include "geometry/polygon.h"

namespace bsp {

template <class Point>
CGAL::Surface_mesh<Point> cgal_mesh_of(std::span<const Polygon> polys) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  std::map<std::tuple<double, double, double>, std::size_t> index;
  const auto id = [&](const Vec3& p) {
    const auto [it, fresh] = index.try_emplace({p.x, p.y, p.z}, points.size());
    if (fresh) points.emplace_back(p.x, p.y, p.z);
    return it->second;
  };
  for (const Polygon& poly : polys)
    for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i)
      faces.push_back({id(poly.verts[0].p), id(poly.verts[i].p), id(poly.verts[i + 1].p)});
  CGAL::Surface_mesh<Point> mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

// CGAL's exact number type is mpq_class when CGAL uses gmpxx (CGAL_USE_GMPXX), else its Gmpq.
template <class Exact>
mpq_class to_mpq(const Exact& e) {
  if constexpr (std::is_same_v<Exact, mpq_class>)
    return e;
  else
    return mpq_class(e.mpq());
}

}  // namespace bsp
