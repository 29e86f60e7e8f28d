#include "tree/tree.h"

namespace bsp {

std::size_t Tree::bytes() const {
  std::size_t total = nodes.size() * sizeof(Node) + planes.bytes() +
                      fragment_plane.size() * sizeof(std::uint32_t) + fragments.size() * sizeof(Polygon);
  for (const auto& f : fragments) total += f.verts.size() * sizeof(Vertex);
  return total;
}

void Tree::freeze() {
  PlanePool renumbered;
  std::vector<std::uint32_t> pair(planes.size() / 2, kNull);  // old pair -> new pair's even index
  const auto remap = [&](std::uint32_t& p) {
    std::uint32_t& to = pair[p >> 1];
    if (to == kNull) to = renumbered.add(planes[p & ~1u]);
    p = to | (p & 1u);
  };
  for (Node& n : nodes)
    if (n.plane != kNull) remap(n.plane);
  for (std::uint32_t& p : fragment_plane) remap(p);
  planes = std::move(renumbered);
}

}  // namespace bsp
