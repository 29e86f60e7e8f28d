#include "tree/tree.h"

namespace bsp {

std::size_t Tree::bytes() const {
  std::size_t total = nodes.size() * sizeof(Node) + planes.bytes() +
                      fragment_plane.size() * sizeof(std::uint32_t) + fragments.size() * sizeof(Polygon);
  for (const auto& f : fragments) total += f.verts.size() * sizeof(Vertex);
  return total;
}

}  // namespace bsp
