#include "metrics/expected_cost.h"

#include <stdexcept>
#include <vector>

#include "geometry/polytope.h"

namespace bsp {

Box root_cell(const Tree& tree, double margin) { return tree.bounds.enlarged(margin); }

ExpectedCosts expected_costs(const Tree& tree, double margin) {
  ExpectedCosts out;
  if (tree.empty()) return out;
  const ConvexPolytope root = ConvexPolytope::box(root_cell(tree, margin));
  out.root_volume = root.volume();
  out.root_area = root.surface_area();
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
    out.e_line += p.cell.surface_area() / out.root_area;
    if (node.is_cell_leaf()) continue;
    out.e_point += p.cell.volume() / out.root_volume;
    const Plane& plane = tree.planes[node.plane];
    if (node.back != kNull) stack.push_back({node.back, p.cell.clipped(plane.flipped(), eps)});
    if (node.front != kNull) stack.push_back({node.front, p.cell.clipped(plane, eps)});
  }
  return out;
}

}  // namespace bsp
