#include "io/doom_tree_stats.h"

#include <algorithm>
#include <vector>

namespace bsp {

namespace {

std::int64_t linedef_sides(const DoomMap& map) {
  std::int64_t n = 0;
  for (const Linedef& l : map.linedefs) n += (l.sidenum[0] != kNoSidedef) + (l.sidenum[1] != kNoSidedef);
  return n;
}

// Depths of the subsectors reached from the root, each once.
std::vector<std::size_t> subsector_depths(const VanillaNodes& n) {
  if (n.nodes.empty()) return std::vector<std::size_t>(n.subsectors.empty() ? 0 : 1, 0);
  std::vector<std::size_t> depths;
  std::vector<bool> seen_node(n.nodes.size()), seen_subsector(n.subsectors.size());
  struct Visit {
    std::size_t node, depth;
  };
  std::vector<Visit> stack{{n.nodes.size() - 1, 0}};
  seen_node.back() = true;
  while (!stack.empty()) {
    const Visit v = stack.back();
    stack.pop_back();
    for (const std::uint16_t child : n.nodes[v.node].child) {
      const std::size_t index = child & ~kSubsectorChild;
      const bool leaf = (child & kSubsectorChild) != 0;
      std::vector<bool>& seen = leaf ? seen_subsector : seen_node;
      if (index >= seen.size() || seen[index]) continue;
      seen[index] = true;
      if (leaf)
        depths.push_back(v.depth + 1);
      else
        stack.push_back({index, v.depth + 1});
    }
  }
  return depths;
}

}  // namespace

DoomTreeStats doom_tree_stats(const DoomMap& map, const VanillaNodes& nodes) {
  DoomTreeStats s{nodes.segs.size(),
                  nodes.subsectors.size(),
                  nodes.nodes.size(),
                  static_cast<std::int64_t>(nodes.segs.size()) - linedef_sides(map),
                  0,
                  0.0};
  const std::vector<std::size_t> depths = subsector_depths(nodes);
  if (depths.empty()) return s;
  s.max_depth = *std::max_element(depths.begin(), depths.end());
  double sum = 0.0;
  for (const std::size_t d : depths) sum += static_cast<double>(d);
  s.mean_depth = sum / static_cast<double>(depths.size());
  return s;
}

}  // namespace bsp
