#include "tree/depth.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace bsp {

std::uint32_t max_depth(const Tree& tree) {
  std::uint32_t deepest = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;
  if (!tree.empty()) stack.push_back({0, 1});
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    for (const std::uint32_t child : {tree.nodes[node].front, tree.nodes[node].back})
      if (child != kNull) stack.push_back({child, depth + 1});
  }
  return deepest;
}

}  // namespace bsp
