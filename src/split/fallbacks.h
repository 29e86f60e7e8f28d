#pragma once
// The autopartition heuristics a free-plane heuristic (halving, octree) may hand a node to when its
// own plane parts nothing: a fragment's own plane always makes progress. The registry cannot be
// consulted for them, as those heuristics are made while it is being built; a test checks that
// each name is a registered autopartition.
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace bsp {

// The names with `first_choice` (one of them) moved to the front: a Choice parameter's default.
inline std::vector<std::string> autopartition_fallbacks(std::string_view first_choice) {
  std::vector<std::string> names{"balanced", "min-relation", "weighted", "quake", "crystal", "naylor", "first", "random"};
  const auto it = std::find(names.begin(), names.end(), first_choice);
  std::rotate(names.begin(), it, it + 1);
  return names;
}

}  // namespace bsp
