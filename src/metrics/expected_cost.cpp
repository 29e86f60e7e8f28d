#include "metrics/expected_cost.h"

#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/polytope.h"

namespace bsp {

Box root_cell(const Tree& tree, double margin) { return tree.bounds.enlarged(margin); }

namespace {

// The two measures of a cell the costs sum: volume and surface area, or for a 2D tree the area and
// perimeter of its section.
std::pair<double, double> measures(const ConvexPolytope& cell, bool planar) {
  if (!planar) return {cell.volume(), cell.surface_area()};
  const ConvexPolytope::Section s = cell.top_section();
  return {s.area, s.perimeter};
}

ExpectedCosts walk(const Tree& tree, double margin, bool planar) {
  ExpectedCosts out;
  if (tree.empty()) return out;
  const ConvexPolytope root = ConvexPolytope::box(root_cell(tree, margin));
  std::tie(out.root_volume, out.root_area) = measures(root, planar);
  if (!(out.root_volume > 0)) throw std::invalid_argument("expected costs need a root cell with volume; use a margin > 0");
  struct Pending {
    std::uint32_t node;
    ConvexPolytope cell;
  };
  std::vector<Pending> stack;
  stack.push_back({0, root});
  const double eps = tree.tol.plane_eps;
  while (!stack.empty()) {
    Pending p = std::move(stack.back());
    stack.pop_back();
    const Node& node = tree.nodes[p.node];
    const auto [volume, area] = measures(p.cell, planar);
    out.e_line += area / out.root_area;
    if (node.is_cell_leaf()) continue;
    out.e_point += volume / out.root_volume;
    const Plane& plane = tree.planes[node.plane];
    if (node.back != kNull) stack.push_back({node.back, p.cell.clipped(plane.flipped(), eps)});
    if (node.front != kNull) stack.push_back({node.front, p.cell.clipped(plane, eps)});
  }
  return out;
}

}  // namespace

ExpectedCosts expected_costs(const Tree& tree, double margin) { return walk(tree, margin, false); }

ExpectedCosts planar_expected_costs(const Tree& tree, double margin) { return walk(tree, margin, true); }

}  // namespace bsp
