#include "solid/solid_tree.h"

#include <algorithm>
#include <string>
#include <utility>

#include "common/errors.h"
#include "geometry/convex_loop.h"

namespace bsp {

Ref SolidTree::add_node(const Plane& plane, std::uint32_t loop, Ref front, Ref back) {
  nodes.push_back({plane, front, back});
  shp.push_back(loop);
  return static_cast<Ref>(nodes.size() - 1);
}

std::size_t SolidTree::bytes() const {
  return nodes.size() * sizeof(SolidNode) + shp.size() * sizeof(std::uint32_t) +
         loops.points.size() * sizeof(Vec3) + loops.start.size() * sizeof(std::uint32_t);
}

Box solid_box(const Box& a, const Box& b) {
  Box box = a;
  box.add(b);
  return box.enlarged(kSolidBoxMargin);
}

namespace {

// The label of node i's missing child: outside in front of a face, inside behind it.
Ref empty_side_label(const Tree& tree, std::uint32_t i, bool front) {
  const FragmentRange frags = tree.fragments_of(i);
  // Faces coplanar within the tolerance may have planes of their own; their facing is the sign
  // of their normal along the node's.
  const Vec3 n = tree.planes[tree.nodes[i].plane].n;
  bool same = true, opposite = true;
  for (std::uint32_t f = frags.begin; f < frags.end; ++f) {
    const bool along = dot(tree.planes[tree.fragment_plane[f]].n, n) > 0;
    same &= along;
    opposite &= !along;
  }
  if (frags.size() == 0 || (same && opposite))
    throw InputError("solid tree: node " + std::to_string(i) +
                     " has an empty side and no face on its plane to label it");
  if (!same && !opposite)
    throw InputError("solid tree: node " + std::to_string(i) +
                     " has an empty side beside faces of both facings (the mesh bounds no solid)");
  return (front == same) ? kOut : kIn;
}

}  // namespace

SolidTree solid_from_tree(const Tree& tree, const Box& box) {
  if (tree.shape != Shape::Strict)
    throw InputError("solid tree: a coarse tree keeps faces in its leaves; build a strict tree");
  SolidTree solid;
  solid.box = box;
  solid.tol = Tolerance::for_extent(box.diagonal());
  if (tree.empty()) return solid;
  solid.nodes.reserve(tree.nodes.size());
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    const Ref front = n.front != kNull ? static_cast<Ref>(n.front) : empty_side_label(tree, i, true);
    const Ref back = n.back != kNull ? static_cast<Ref>(n.back) : empty_side_label(tree, i, false);
    solid.add_node(tree.planes[n.plane], 0, front, back);
  }
  solid.root = 0;
  compute_subhyperplanes(solid);
  return solid;
}

void compute_subhyperplanes(SolidTree& solid) {
  solid.loops = {};
  solid.shp.assign(solid.nodes.size(), 0);
  struct Item {
    Ref node;
    std::uint32_t depth;
    Plane towards;  // the parent's half-space containing this node (unused at the root)
  };
  std::vector<Item> stack;
  std::vector<Plane> path;
  std::vector<Vec3> loop, front, back;
  if (!is_leaf(solid.root)) stack.push_back({solid.root, 0, {}});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    path.resize(item.depth);
    if (item.depth > 0) path.back() = item.towards;
    const SolidNode& node = solid.nodes[item.node];
    loop = plane_in_box(node.plane, solid.box);
    for (const Plane& p : path) {
      if (loop.empty()) break;
      // Wholly on the kept side, the loop is what the cut would keep, vertex for vertex: most
      // ancestors of a chain's deep nodes are such, and the test reads the distances only.
      if (std::all_of(loop.begin(), loop.end(), [&](const Vec3& v) { return p.distance(v) >= 0; })) continue;
      // A plane coplanar with an ancestor's keeps its loop; any other is cut where the distance
      // changes sign: snapping vertices within eps to the plane would move the cut along an edge
      // that grazes the plane by far more than eps.
      if (classify_loop(loop, node.plane, p, solid.tol.plane_eps) == Side::Coplanar) continue;
      split_loop(loop, p, 0.0, front, back);
      loop.swap(front);
    }
    solid.shp[item.node] = solid.loops.add(loop);
    if (!is_leaf(node.back)) stack.push_back({node.back, item.depth + 1, node.plane.flipped()});
    if (!is_leaf(node.front)) stack.push_back({node.front, item.depth + 1, node.plane});
  }
}

PointClass classify_point(const SolidTree& solid, const Vec3& p) {
  bool in = false, out = false;
  std::vector<Ref> stack{solid.root};
  while (!stack.empty()) {
    const Ref r = stack.back();
    stack.pop_back();
    if (is_leaf(r)) {
      (r == kIn ? in : out) = true;
      continue;
    }
    const SolidNode& node = solid.nodes[r];
    const double d = node.plane.distance(p);
    if (d >= -solid.tol.plane_eps) stack.push_back(node.front);
    if (d <= solid.tol.plane_eps) stack.push_back(node.back);
  }
  return in && out ? PointClass::On : (in ? PointClass::In : PointClass::Out);
}

SolidSize solid_size(const SolidTree& solid) { return solid_size_of(solid.nodes, solid.root); }

SolidTree complemented(SolidTree solid) {
  for (SolidNode& n : solid.nodes) {
    if (is_leaf(n.front)) n.front = flip_label(n.front);
    if (is_leaf(n.back)) n.back = flip_label(n.back);
  }
  if (is_leaf(solid.root)) solid.root = flip_label(solid.root);
  return solid;
}

}  // namespace bsp
