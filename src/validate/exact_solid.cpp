#include "validate/exact_solid.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "validate/cgal_mesh.h"

namespace bsp {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

struct ExactSolid::Impl {
  Mesh mesh;
  AabbTree tree;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<Mesh, Kernel>> side;

  explicit Impl(Mesh m) : mesh(std::move(m)) {
    tree.insert(faces(mesh).first, faces(mesh).second, mesh);
    tree.accelerate_distance_queries();
    side = std::make_unique<CGAL::Side_of_triangle_mesh<Mesh, Kernel>>(mesh);
  }
};

ExactSolid::ExactSolid(std::span<const Polygon> polys) : impl_(std::make_unique<Impl>(cgal_mesh_of<Point>(polys))) {}
ExactSolid::ExactSolid(const ExactSolid& other) : impl_(std::make_unique<Impl>(other.impl_->mesh)) {}
ExactSolid::~ExactSolid() = default;

ExactSide ExactSolid::side(const Vec3& p) const {
  switch ((*impl_->side)(Point(p.x, p.y, p.z))) {
    case CGAL::ON_BOUNDED_SIDE: return ExactSide::Inside;
    case CGAL::ON_BOUNDARY: return ExactSide::Boundary;
    default: return ExactSide::Outside;
  }
}

double ExactSolid::distance(const Vec3& p) const {
  return std::sqrt(CGAL::to_double(impl_->tree.squared_distance(Point(p.x, p.y, p.z))));
}

double ExactSolid::volume() const { return CGAL::to_double(PMP::volume(impl_->mesh)); }
std::size_t ExactSolid::triangles() const { return impl_->mesh.number_of_faces(); }

std::size_t ExactSolid::self_intersecting_pairs() const {
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections(impl_->mesh, std::back_inserter(pairs));
  return pairs.size();
}

struct CorefineAccess {
  static Mesh mesh(const ExactSolid& s) { return s.impl_->mesh; }
};

CorefineResult corefine(const ExactSolid& a, const ExactSolid& b, SetOp op) {
  const auto one = [](Mesh x, Mesh y, SetOp o) {
    Mesh out;
    bool ok = false;
    try {
      switch (o) {
        case SetOp::Union: ok = PMP::corefine_and_compute_union(x, y, out); break;
        case SetOp::Intersection: ok = PMP::corefine_and_compute_intersection(x, y, out); break;
        default: ok = PMP::corefine_and_compute_difference(x, y, out); break;
      }
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("CGAL corefinement failed: ") + e.what());
    }
    if (!ok) throw std::runtime_error("CGAL corefinement failed (self-intersecting or non-manifold operands)");
    return out;
  };
  const Mesh ma = CorefineAccess::mesh(a), mb = CorefineAccess::mesh(b);
  if (op == SetOp::SymmetricDifference) {
    const Mesh d1 = one(ma, mb, SetOp::Difference), d2 = one(mb, ma, SetOp::Difference);
    return {CGAL::to_double(PMP::volume(d1)) + CGAL::to_double(PMP::volume(d2)),
            d1.number_of_faces() + d2.number_of_faces()};
  }
  const Mesh out = one(ma, mb, op);
  return {CGAL::to_double(PMP::volume(out)), out.number_of_faces()};
}

}  // namespace bsp
