#include "solid/solid_tree.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "common/errors.h"
#include "geometry/convex_loop.h"
#include "geometry/polygon.h"
#include "geometry/polytope.h"

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
      split_loop(loop, p, solid.tol.plane_eps, front, back);
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

SolidSize solid_size(const SolidTree& solid) {
  SolidSize size;
  std::vector<std::pair<Ref, std::uint64_t>> stack{{solid.root, 0}};
  while (!stack.empty()) {
    const auto [r, depth] = stack.back();
    stack.pop_back();
    size.depth = std::max(size.depth, depth);
    if (is_leaf(r)) {
      ++(r == kIn ? size.in_leaves : size.out_leaves);
      continue;
    }
    ++size.nodes;
    stack.push_back({solid.nodes[r].back, depth + 1});
    stack.push_back({solid.nodes[r].front, depth + 1});
  }
  return size;
}

namespace {

// A cell as its face loops, clipped without a tolerance: a vertex goes by the sign of its distance,
// so no part of a cell is given to the wrong side, however thin. The cap is every cut point,
// ordered by angle: points of one edge cut from its two faces differ by rounding and give a
// zero-length edge, which adds nothing to the volume.
using Cell = LoopPool;

Cell box_cell(const Box& b) {
  Cell cell;
  const ConvexPolytope box = ConvexPolytope::box(b);
  for (std::size_t f = 0; f < box.face_count(); ++f) cell.add(box.face(f));
  return cell;
}

void add_cap(Cell& cell, std::vector<Vec3>& cut, const Vec3& outward) {
  if (cut.size() < 3) return;
  Vec3 c;
  for (const Vec3& p : cut) c += p;
  c = c / static_cast<double>(cut.size());
  const Vec3 u = normalize(std::abs(outward.x) < 0.9 ? cross(outward, Vec3{1, 0, 0}) : cross(outward, Vec3{0, 1, 0}));
  const Vec3 v = cross(outward, u);
  std::vector<std::pair<double, Vec3>> by_angle;
  for (const Vec3& p : cut) by_angle.push_back({std::atan2(dot(p - c, v), dot(p - c, u)), p});
  std::sort(by_angle.begin(), by_angle.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  cut.clear();
  for (const auto& a : by_angle) cut.push_back(a.second);
  cell.add(cut);
}

// The parts of the cell in front of and behind the plane; either may come back empty.
void split_cell(const Cell& cell, const Plane& plane, Cell& front, Cell& back) {
  front = {};
  back = {};
  bool any_front = false, any_back = false;
  for (const Vec3& p : cell.points) {
    const double d = plane.distance(p);
    any_front |= d > 0;
    any_back |= d < 0;
  }
  if (!any_back || !any_front) {
    (any_back ? back : front) = cell;
    return;
  }
  std::vector<Vec3> f, b, cut;
  for (std::uint32_t i = 0; i < cell.size(); ++i) {
    const std::span<const Vec3> loop = cell[i];
    split_loop(loop, plane, 0.0, f, b);
    if (!f.empty()) front.add(f);
    if (!b.empty()) back.add(b);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3& p = loop[k];
      const Vec3& q = loop[k + 1 == loop.size() ? 0 : k + 1];
      const double dp = plane.distance(p), dq = plane.distance(q);
      if (dp == 0) cut.push_back(p);
      if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) cut.push_back(p + (q - p) * (dp / (dp - dq)));
    }
  }
  std::vector<Vec3> cap = cut;
  add_cap(front, cap, -plane.n);
  add_cap(back, cut, plane.n);
}

double cell_volume(const Cell& cell) {
  double v = 0;
  for (std::uint32_t i = 0; i < cell.size(); ++i) v += dot(newell_normal(cell[i]), cell[i].front());
  return v / 6.0;
}

}  // namespace

double solid_volume(const SolidTree& solid) {
  double volume = 0;
  std::vector<std::pair<Ref, Cell>> stack;
  stack.emplace_back(solid.root, box_cell(solid.box));
  Cell front, back;
  while (!stack.empty()) {
    auto [r, cell] = std::move(stack.back());
    stack.pop_back();
    if (is_leaf(r)) {
      if (r == kIn) volume += cell_volume(cell);
      continue;
    }
    const SolidNode& node = solid.nodes[r];
    split_cell(cell, node.plane, front, back);
    if (node.back != kOut && !back.points.empty()) stack.emplace_back(node.back, std::move(back));
    if (node.front != kOut && !front.points.empty()) stack.emplace_back(node.front, std::move(front));
  }
  return volume;
}

SolidTree complemented(SolidTree solid) {
  for (SolidNode& n : solid.nodes) {
    if (is_leaf(n.front)) n.front = flip_label(n.front);
    if (is_leaf(n.back)) n.back = flip_label(n.back);
  }
  if (is_leaf(solid.root)) solid.root = flip_label(solid.root);
  return solid;
}

}  // namespace bsp
