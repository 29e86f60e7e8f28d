#include "tree/tree.h"

namespace bsp {

std::size_t Tree::bytes() const {
  return nodes.size() * sizeof(Node) + planes.bytes() + fragments.bytes() +
         fragment_plane.size() * sizeof(std::uint32_t);
}

}  // namespace bsp
