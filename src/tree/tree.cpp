#include "tree/tree.h"

namespace bsp {

std::size_t Tree::bytes() const {
  std::size_t total = nodes.capacity() * sizeof(Node) + planes.bytes() +
                      fragment_plane.capacity() * sizeof(std::uint32_t) +
                      fragments.capacity() * sizeof(Polygon);
  for (const auto& f : fragments) total += f.verts.capacity() * sizeof(Vertex);
  return total;
}

}  // namespace bsp
