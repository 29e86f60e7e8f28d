// CGAL's Nef polyhedra as a second reference for set operations, in a translation unit of their own:
// their exact-construction kernel is the slowest CGAL code to compile.
#include "validate/exact_solid.h"
#include "validate/exact_measure.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>

#include <chrono>
#include <stdexcept>
#include <vector>

#include "validate/cgal_mesh.h"

namespace bsp {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Nef = CGAL::Nef_polyhedron_3<Kernel>;
namespace PMP = CGAL::Polygon_mesh_processing;

// A leaf's convex polygons with their double coordinates taken exactly, vertices shared.
Nef nef_of(std::span<const Polygon> polys) {
  const Mesh mesh = cgal_mesh_of<Point>(polys);
  if (!CGAL::is_closed(mesh)) throw std::runtime_error("a leaf is not closed");
  return Nef(mesh);
}

Nef combine(const Nef& x, const Nef& y, StepKind kind) {
  if (kind == StepKind::Union) return x + y;
  if (kind == StepKind::Intersection) return x * y;
  return x - y;
}

// The hull of the operands' vertices; fewer than four points off one plane: the empty solid.
Nef hull(std::span<const Nef> operands) {
  std::vector<Point> points;
  for (const Nef& n : operands)
    for (auto v = n.vertices_begin(); v != n.vertices_end(); ++v) points.push_back(v->point());
  if (points.size() < 4) return Nef();
  Mesh out;
  CGAL::convex_hull_3(points.begin(), points.end(), out);
  if (out.number_of_faces() < 4 || PMP::volume(out) == 0) return Nef();  // coplanar points: no solid
  return Nef(out);
}

Nef fold(std::vector<Nef> ops, StepKind kind, FoldOrder order, std::uint64_t& operations) {
  if (ops.empty()) return Nef();
  if (order == FoldOrder::Balanced && kind == StepKind::Difference && ops.size() > 2) {
    Nef cut = fold(std::vector<Nef>(ops.begin() + 1, ops.end()), StepKind::Union, order, operations);
    ++operations;
    return ops[0] - cut;
  }
  if (order == FoldOrder::Balanced && kind != StepKind::Difference) {
    while (ops.size() > 1) {
      std::vector<Nef> next;
      for (std::size_t i = 0; i + 1 < ops.size(); i += 2, ++operations) next.push_back(combine(ops[i], ops[i + 1], kind));
      if (ops.size() % 2 == 1) next.push_back(ops.back());
      ops = std::move(next);
    }
    return ops[0];
  }
  Nef result = ops[0];
  for (std::size_t i = 1; i < ops.size(); ++i, ++operations) result = combine(result, ops[i], kind);
  return result;
}


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

ExactProgramVolume exact_nef_program(std::span<const std::vector<Polygon>> leaves, std::span<const Step> steps, FoldOrder order,
                                     const std::vector<std::vector<Polygon>>* hulls) {
  std::size_t next_hull = 0;
  const auto start = std::chrono::steady_clock::now();
  ExactProgramVolume out;
  std::vector<Nef> stack;
  try {
    for (const Step& step : steps) {
      if (step.kind == StepKind::Leaf) {
        stack.push_back(nef_of(leaves[step.count]));
        continue;
      }
      if (step.count > stack.size()) throw std::logic_error("exact_nef_program: a step pops more operands than pushed");
      const auto first = stack.end() - step.count;
      Nef result;  // empty
      if (step.kind == StepKind::Hull && hulls) {
        const std::vector<Polygon>& given = (*hulls)[next_hull++];
        if (!given.empty()) result = nef_of(given);
      } else if (step.kind == StepKind::Hull) {
        result = hull(std::span<const Nef>(&*first, step.count));
        ++out.operations;
      } else {
        result = fold(std::vector<Nef>(first, stack.end()), step.kind, order, out.operations);
      }
      stack.erase(first, stack.end());
      stack.push_back(std::move(result));
    }
    if (stack.size() != 1) throw std::logic_error("exact_nef_program: the program leaves " + std::to_string(stack.size()) + " operands");
    // As a soup: a non-manifold result has no polygon mesh, but its triangles still bound its
    // volume (divergence theorem: six times it is the sum of the triangles' determinants).
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> triangles;
    CGAL::convert_nef_polyhedron_to_polygon_soup(stack[0], points, triangles, true);
    Kernel::FT six = 0;
    for (const auto& t : triangles)
      six += CGAL::determinant(points[t[0]] - CGAL::ORIGIN, points[t[1]] - CGAL::ORIGIN, points[t[2]] - CGAL::ORIGIN);
    mpq_class v = to_mpq(CGAL::exact(six)) / 6;
    v.canonicalize();
    out.volume = v.get_str();
    out.volume_double = v.get_d();
    out.triangles = triangles.size();
  } catch (const std::runtime_error& e) {
    out.error = e.what();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bsp
