#include "tree/exact_traverse.h"

#include <cmath>

namespace bsp {

std::optional<GridPoint> snap_eye(const Grid& grid, const Vec3& p) {
  const Vec3 d = (p - grid.origin()) / grid.step();
  const double kLimit = std::ldexp(1.0, kEyeBits) - 0.5;
  if (!(std::abs(d.x) < kLimit && std::abs(d.y) < kLimit && std::abs(d.z) < kLimit)) return std::nullopt;
  return GridPoint{std::llround(d.x), std::llround(d.y), std::llround(d.z)};
}

int side_of_eye(const GridPlane& p, const GridPoint& e) {
  using Wide = WideInt<3>;
  const Wide v = Wide(p.a) * Wide(e.x) + Wide(p.b) * Wide(e.y) + Wide(p.c) * Wide(e.z) + Wide(p.d);
  return v.sign();
}

std::vector<std::uint32_t> exact_visibility_order(const ExactTree& t, const GridPoint& eye, Order order) {
  std::vector<std::uint32_t> out;
  out.reserve(t.fragments.size());
  if (t.tree.empty()) return out;
  const bool back_to_front = order == Order::BackToFront;
  // A pending entry is a node to visit, or (own = true) a node whose own fragments are due.
  struct Pending {
    std::uint32_t node;
    bool own;
  };
  std::vector<Pending> stack{{0, false}};
  while (!stack.empty()) {
    const Pending p = stack.back();
    stack.pop_back();
    const Node& n = t.tree.nodes[p.node];
    const FragmentRange r = t.tree.fragments_of(p.node);
    if (p.own) {
      for (std::uint32_t f = r.begin; f < r.end; ++f) out.push_back(f);
      continue;
    }
    if (n.is_cell_leaf()) {
      for (int pass = 0; pass < 2; ++pass)
        for (std::uint32_t f = r.begin; f < r.end; ++f) {
          const bool faces_eye = side_of_eye(t.plane(t.tree.fragment_plane[f]), eye) >= 0;
          if ((pass == 0) == (faces_eye == back_to_front)) out.push_back(f);
        }
      continue;
    }
    // Far side first: pushed last. The eye in front (or on the plane) makes the back side far.
    const bool back_far = (side_of_eye(t.plane(n.plane), eye) >= 0) == back_to_front;
    const std::uint32_t near = back_far ? n.front : n.back, far = back_far ? n.back : n.front;
    if (near != kNull) stack.push_back({near, false});
    stack.push_back({p.node, true});
    if (far != kNull) stack.push_back({far, false});
  }
  return out;
}

}  // namespace bsp
