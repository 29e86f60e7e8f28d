// CGAL's Nef polyhedra as a second reference for set operations, in a translation unit of their own:
// their exact-construction kernel is the slowest CGAL code to compile.
#include "validate/exact_solid.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <chrono>
#include <vector>

#include "validate/cgal_mesh.h"

namespace bsp {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Nef = CGAL::Nef_polyhedron_3<Kernel>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

NefResult nef_set_operation(std::span<const Polygon> a, std::span<const Polygon> b, SetOp op) {
  const Mesh ma = cgal_mesh_of<Point>(a), mb = cgal_mesh_of<Point>(b);
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
