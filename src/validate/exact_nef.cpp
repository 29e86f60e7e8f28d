// CGAL's Nef polyhedra as a second reference for set operations, in a translation unit of their own:
// their exact-construction kernel is the slowest CGAL code to compile.
#include "validate/exact_solid.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <chrono>
#include <map>
#include <tuple>
#include <vector>

namespace bsp {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Nef = CGAL::Nef_polyhedron_3<Kernel>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh mesh_of(std::span<const Polygon> polys) {
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
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

}  // namespace

NefResult nef_set_operation(std::span<const Polygon> a, std::span<const Polygon> b, SetOp op) {
  const Mesh ma = mesh_of(a), mb = mesh_of(b);
  const auto start = std::chrono::steady_clock::now();
  const Nef na(ma), nb(mb);
  Nef out;
  switch (op) {
    case SetOp::Union: out = na + nb; break;
    case SetOp::Intersection: out = na * nb; break;
    case SetOp::Difference: out = na - nb; break;
    case SetOp::SymmetricDifference: out = na ^ nb; break;
  }
  NefResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Mesh result;
  CGAL::convert_nef_polyhedron_to_polygon_mesh(out, result);
  PMP::triangulate_faces(result);
  r.volume = CGAL::to_double(PMP::volume(result));
  return r;
}

}  // namespace bsp
