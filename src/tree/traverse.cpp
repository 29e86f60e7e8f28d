#include "tree/traverse.h"

namespace bsp {

std::vector<std::uint32_t> visibility_order(const Tree& tree, const Vec3& eye, Order order,
                                            TraversalCounters* counters) {
  std::vector<std::uint32_t> out;
  out.reserve(tree.fragments.size());
  const TraversalCounters c = traverse(tree, eye, order, [&](std::uint32_t i) { out.push_back(i); });
  if (counters) *counters = c;
  return out;
}

}  // namespace bsp
