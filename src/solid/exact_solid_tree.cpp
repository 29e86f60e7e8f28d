#include "solid/exact_solid_tree.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "common/errors.h"

namespace bsp {

namespace {

constexpr std::uint32_t kNone = FragmentStore::kNone;

Int128 abs128(Int128 v) { return v < 0 ? -v : v; }

// The box's faces as grid planes facing inwards: e_axis . x - lo >= 0 and -e_axis . x + hi >= 0.
GridPlane box_face(int axis, bool high, const GridBox& box) {
  const std::int64_t lo[] = {box.lo.x, box.lo.y, box.lo.z}, hi[] = {box.hi.x, box.hi.y, box.hi.z};
  GridPlane p;
  Int128* coef[] = {&p.a, &p.b, &p.c};
  *coef[axis] = high ? -1 : 1;
  p.d = high ? Int128{hi[axis]} : -Int128{lo[axis]};
  return p;
}

}  // namespace

ExactSolidSpace::ExactSolidSpace(const Grid& grid, const GridBox& box)
    : box_(box), pool_(grid), shps_(pool_, kReusedSpan, ExactFragments::Copies::None) {
  for (int axis = 0; axis < 3; ++axis)
    for (const bool high : {false, true}) box_planes_[2 * axis + high] = pool_.add(box_face(axis, high, box));
}

std::unique_ptr<ExactSolidSpace> ExactSolidSpace::for_box(const Box& box) {
  if (box.empty() || !is_finite(box.lo) || !is_finite(box.hi))
    throw std::invalid_argument("an exact solid space needs a finite, non-empty box");
  const Grid grid = Grid::for_box(box);
  // Every point of the box is in the grid's range (grid.h); one step outwards keeps the rounded
  // corners around the box, and is still in range (the range has more than 2^39 steps to spare).
  GridPoint lo = *grid.snap(box.lo), hi = *grid.snap(box.hi);
  lo = {lo.x - 1, lo.y - 1, lo.z - 1};
  hi = {hi.x + 1, hi.y + 1, hi.z + 1};
  return std::make_unique<ExactSolidSpace>(grid, GridBox{lo, hi});
}

// The plane is a graph over the two axes u, v other than its normal's largest component k, so it
// meets the box's four faces across u and v in a quadrilateral (its vertices may lie far outside the
// box: no bound of the predicates depends on where a vertex is); the faces across k clip it. Seen
// from +k with (u, v, k) right-handed, the faces low-v, high-u, high-v, low-u come counter-clockwise
// (at each vertex det(n, b_i, b_i+1) = n . (b_i x b_i+1) = n_k > 0); a normal with n_k < 0 reverses them.
std::uint32_t ExactSolidSpace::plane_in_box(std::uint32_t plane) {
  const GridPlane h = pool_[plane];
  const Int128 n[] = {h.a, h.b, h.c};
  int k = 0;
  for (int j = 1; j < 3; ++j)
    if (abs128(n[j]) > abs128(n[k])) k = j;
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  std::uint32_t bounds[] = {box_plane(v, false), box_plane(u, true), box_plane(v, true), box_plane(u, false)};
  if (n[k] < 0) std::reverse(std::begin(bounds), std::end(bounds));
  std::uint32_t id = shps_.add_pooled(plane, bounds);
  id = clip(id, box_plane(k, false));
  return id == kNone ? kNone : clip(id, box_plane(k, true));
}

std::uint32_t ExactSolidSpace::clip(std::uint32_t id, std::uint32_t plane) {
  const std::uint32_t front = shps_.clip(id, plane);
  return front == FragmentStore::kNone ? kNone : front;
}

Ref ExactSolidTree::add_node(std::uint32_t plane, std::uint32_t shp_id, Ref front, Ref back) {
  if (nodes.size() >= 0x7ffffffeu) throw std::length_error("an exact solid tree has more than 2^31 - 2 nodes");
  nodes.push_back({plane, front, back});
  shp.push_back(shp_id);
  return static_cast<Ref>(nodes.size() - 1);
}

namespace {

// The label of node i's missing child, as solid_tree.cpp's empty_side_label, with facing decided
// by index: a face on the node's plane has the node's pooled plane or its opposite.
Ref empty_side_label(const Tree& tree, std::uint32_t i, bool front) {
  const FragmentRange frags = tree.fragments_of(i);
  const std::uint32_t plane = tree.nodes[i].plane;
  bool same = true, opposite = true;
  for (std::uint32_t f = frags.begin; f < frags.end; ++f) {
    same &= tree.fragment_plane[f] == plane;
    opposite &= tree.fragment_plane[f] == PlanePool::flip(plane);
  }
  if (frags.size() == 0)
    throw InputError("solid tree: node " + std::to_string(i) + " has an empty side and no face on its plane to label it");
  if (!same && !opposite)
    throw InputError("solid tree: node " + std::to_string(i) +
                     " has an empty side beside faces of both facings (the mesh bounds no solid)");
  return front == same ? kOut : kIn;
}

// shp(v) for every node: the plane's polygon in the box, clipped by each ancestor's half-space
// towards v. Not empty, by the invariants (exact_solid_tree.h): a strict tree's node holds a face
// inside its region, and a free plane separates the region's faces or the build replaced it.
void compute_subhyperplanes(ExactSolidTree& solid, ExactSolidSpace& space) {
  struct Item {
    Ref node;
    std::uint32_t depth;
    std::uint32_t towards;  // the parent's plane oriented towards the node (unused at the root)
  };
  std::vector<Item> stack;
  std::vector<std::uint32_t> path;
  if (!is_leaf(solid.root)) stack.push_back({solid.root, 0, 0});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    path.resize(item.depth);
    if (item.depth > 0) path.back() = item.towards;
    const ExactSolidNode node = solid.nodes[item.node];
    std::uint32_t id = space.plane_in_box(node.plane);
    for (std::size_t i = 0; i < path.size() && id != kNone; ++i) id = space.clip(id, path[i]);
    if (id == kNone) throw std::logic_error("exact solid tree: a node's plane misses its region");
    solid.shp[item.node] = id;
    if (!is_leaf(node.back)) stack.push_back({node.back, item.depth + 1, PlanePool::flip(node.plane)});
    if (!is_leaf(node.front)) stack.push_back({node.front, item.depth + 1, node.plane});
  }
}

}  // namespace

ExactSolidTree exact_solid_from_tree(const ExactTree& et, ExactSolidSpace& space) {
  const Tree& tree = et.tree;
  if (tree.shape != Shape::Strict)
    throw InputError("solid tree: a coarse tree keeps faces in its leaves; build a strict tree");
  ExactSolidTree solid;
  if (tree.empty()) return solid;
  std::vector<std::uint32_t> pair(et.planes.size());
  for (std::size_t k = 0; k < et.planes.size(); ++k) pair[k] = space.pool().add(et.planes[k]);
  solid.nodes.reserve(tree.nodes.size());
  for (std::uint32_t i = 0; i < tree.nodes.size(); ++i) {
    const Node& n = tree.nodes[i];
    const Ref front = n.front != kNull ? static_cast<Ref>(n.front) : empty_side_label(tree, i, true);
    const Ref back = n.back != kNull ? static_cast<Ref>(n.back) : empty_side_label(tree, i, false);
    solid.add_node(pair[n.plane >> 1] ^ (n.plane & 1u), kNone, front, back);
  }
  solid.root = 0;
  compute_subhyperplanes(solid, space);
  return solid;
}

ExactSolidBuild build_exact_solid(std::span<const Polygon> polys, Splitter& splitter, ExactSolidSpace& space,
                                  BuildOptions options) {
  options.shape = Shape::Strict;
  const ExactTree tree = build_exact_tree(polys, splitter, options, &space.grid());
  ExactSolidBuild out;
  out.build = tree.tree.stats;
  out.exact = tree.exact;
  out.fragments = tree.fragments.size();
  const auto start = std::chrono::steady_clock::now();
  out.solid = exact_solid_from_tree(tree, space);
  out.label_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

PointClass classify_point(const ExactSolidTree& solid, const ExactSolidSpace& space, const GridPoint& p) {
  bool in = false, out = false;
  std::vector<Ref> stack{solid.root};
  while (!stack.empty()) {
    const Ref r = stack.back();
    stack.pop_back();
    if (is_leaf(r)) {
      (r == kIn ? in : out) = true;
      continue;
    }
    const ExactSolidNode& node = solid.nodes[r];
    const int side = space.pool()[node.plane].side(p);
    if (side >= 0) stack.push_back(node.front);
    if (side <= 0) stack.push_back(node.back);
  }
  return in && out ? PointClass::On : (in ? PointClass::In : PointClass::Out);
}

SolidSize solid_size(const ExactSolidTree& solid) { return solid_size_of(solid.nodes, solid.root); }

std::string check_exact_solid(const ExactSolidTree& solid, ExactSolidSpace& space) {
  if (solid.shp.size() != solid.nodes.size()) return "sub-hyperplanes and nodes differ in number";
  struct Item {
    Ref node;
    std::uint32_t depth;
    std::uint32_t towards;
  };
  std::vector<Item> stack;
  std::vector<std::uint32_t> path;
  if (!is_leaf(solid.root)) stack.push_back({solid.root, 0, 0});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node < 0 || static_cast<std::size_t>(item.node) >= solid.nodes.size())
      return "a link past the nodes: " + std::to_string(item.node);
    if (item.depth > solid.nodes.size()) return "a cycle through node " + std::to_string(item.node);  // else endless
    path.resize(item.depth);
    if (item.depth > 0) path.back() = item.towards;
    const ExactSolidNode& n = solid.nodes[item.node];
    const std::string at = "node " + std::to_string(item.node) + ": ";
    if (space.shps().plane(solid.shp[item.node]) != n.plane) return at + "its sub-hyperplane lies on another plane";
    for (const std::uint32_t p : path) {
      if (PlanePool::coplanar(p, n.plane)) return at + "an ancestor has its plane";
      const Side s = space.shps().classify(solid.shp[item.node], p);
      if (s != Side::Front) return at + "its sub-hyperplane reaches behind an ancestor's plane";
    }
    if (!is_leaf(n.back)) stack.push_back({n.back, item.depth + 1, PlanePool::flip(n.plane)});
    if (!is_leaf(n.front)) stack.push_back({n.front, item.depth + 1, n.plane});
  }
  return {};
}

namespace {

// A piece of a sub-hyperplane on its way down a subtree; `owned` when it is a part made on the way
// (released when done), not the node's own shp.
struct Piece {
  std::uint32_t id;
  Ref at;
  bool owned;
};

// Pushes polygon `id` on plane h down the subtree at `root`; `front` says on which side of h lie
// the points it stands for. Appends to `out` the pieces that reach leaves, with the leaf in `at`.
void push_down(ExactSolidSpace& space, const ExactSolidTree& solid, std::uint32_t id, bool owned, Ref root,
               std::uint32_t h, bool front, std::vector<Piece>& out) {
  ExactFragments& store = space.shps();
  std::vector<Piece> stack{{id, root, owned}};
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    if (is_leaf(p.at)) {
      out.push_back(p);
      continue;
    }
    const ExactSolidNode& node = solid.nodes[p.at];
    if (PlanePool::coplanar(node.plane, h)) {
      stack.push_back({p.id, node.child((node.plane == h) == front), p.owned});
      continue;
    }
    switch (store.classify(p.id, node.plane)) {
      case Side::Front: stack.push_back({p.id, node.front, p.owned}); break;
      case Side::Back: stack.push_back({p.id, node.back, p.owned}); break;
      case Side::Coplanar:  // only on the same plane, handled above
      case Side::Spanning: {
        const ExactFragments::Parts parts = store.split(p.id, node.plane, !p.owned);
        stack.push_back({parts.back, node.back, true});
        stack.push_back({parts.front, node.front, true});
        break;
      }
    }
  }
}

PlanePolygon facing_out(PlanePolygon poly, bool front_is_out) {
  if (front_is_out) return poly;
  poly.support = -poly.support;
  std::reverse(poly.bounds.begin(), poly.bounds.end());
  return poly;
}

}  // namespace

std::vector<PlanePolygon> exact_solid_boundary(const ExactSolidTree& solid, ExactSolidSpace& space) {
  ExactFragments& store = space.shps();
  std::vector<PlanePolygon> faces;
  std::vector<Piece> fronts, backs;
  std::vector<Ref> stack;
  if (!is_leaf(solid.root)) stack.push_back(solid.root);
  while (!stack.empty()) {
    const Ref v = stack.back();
    stack.pop_back();
    const ExactSolidNode& node = solid.nodes[v];
    fronts.clear();
    push_down(space, solid, solid.shp[v], false, node.front, node.plane, true, fronts);
    for (const Piece& f : fronts) {
      backs.clear();
      push_down(space, solid, f.id, f.owned, node.back, node.plane, false, backs);
      for (const Piece& b : backs) {
        if (f.at != b.at) faces.push_back(facing_out(store.polygon(b.id), f.at == kOut));
        if (b.owned) store.release(b.id);
      }
    }
    if (!is_leaf(node.back)) stack.push_back(node.back);
    if (!is_leaf(node.front)) stack.push_back(node.front);
  }
  return faces;
}

}  // namespace bsp
