#include "tree/tree.h"

namespace bsp {

std::size_t Tree::bytes() const {
  std::size_t total = nodes.size() * sizeof(Node) + planes.bytes() +
                      fragment_plane.size() * sizeof(std::uint32_t) + fragments.size() * sizeof(Polygon);
  for (const auto& f : fragments) total += f.verts.size() * sizeof(Vertex);
  return total;
}

namespace {

// Node indices in pre-order, front child first, from an explicit stack.
std::vector<std::uint32_t> preorder(const std::vector<Node>& nodes) {
  std::vector<std::uint32_t> order;
  if (nodes.empty()) return order;
  order.reserve(nodes.size());
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    order.push_back(n);
    if (nodes[n].back != kNull) stack.push_back(nodes[n].back);
    if (nodes[n].front != kNull) stack.push_back(nodes[n].front);
  }
  return order;
}

}  // namespace

void Tree::order_nodes() {
  const std::vector<std::uint32_t> order = preorder(nodes);
  bool in_order = true;
  for (std::uint32_t i = 0; i < order.size() && in_order; ++i)
    in_order = order[i] == i && (i == 0 || nodes[i].first == nodes[i - 1].first + nodes[i - 1].count);
  if (in_order) return;
  std::vector<std::uint32_t> new_index(nodes.size(), kNull);
  for (std::uint32_t i = 0; i < order.size(); ++i) new_index[order[i]] = i;
  std::vector<Node> ordered_nodes;
  std::vector<Polygon> ordered_fragments;
  std::vector<std::uint32_t> ordered_planes;
  ordered_nodes.reserve(order.size());
  ordered_fragments.reserve(fragments.size());
  ordered_planes.reserve(fragments.size());
  for (const std::uint32_t old : order) {
    Node n = nodes[old];
    if (n.front != kNull) n.front = new_index[n.front];
    if (n.back != kNull) n.back = new_index[n.back];
    const std::uint32_t first = n.first;
    n.first = static_cast<std::uint32_t>(ordered_fragments.size());
    for (std::uint32_t f = first; f < first + n.count; ++f) {
      ordered_fragments.push_back(std::move(fragments[f]));
      ordered_planes.push_back(fragment_plane[f]);
    }
    ordered_nodes.push_back(n);
  }
  nodes = std::move(ordered_nodes);
  fragments = std::move(ordered_fragments);
  fragment_plane = std::move(ordered_planes);
}

void Tree::freeze() {
  order_nodes();
  PlanePool renumbered;
  std::vector<std::uint32_t> pair(planes.size() / 2, kNull);  // old pair -> new pair's even index
  const auto remap = [&](std::uint32_t& p) {
    std::uint32_t& to = pair[p >> 1];
    if (to == kNull) to = renumbered.append_distinct(planes[p & ~1u]);
    p = to | (p & 1u);
  };
  for (Node& n : nodes)
    if (n.plane != kNull) remap(n.plane);
  for (std::uint32_t& p : fragment_plane) remap(p);
  planes = std::move(renumbered);
}

}  // namespace bsp
