#pragma once
// A reusable checker of what every BSP tree must satisfy, whatever heuristic built it:
//  1. structure: every node is reached from the root exactly once, in the stored order (pre-order,
//     front child first: the traversal's sweep relies on it); fragment ranges partition the
//     fragment array;
//  2. separation: every fragment in a node's front subtree lies in front of or on the node's plane
//     (within plane_eps), every one in its back subtree behind or on it;
//  3. storage: fragments stored at a strict node are coplanar with its plane; a coarse leaf holds a
//     convex set;
//  4. conservation: the fragments' area + dropped area = input area (relative 1e-9), and no source's
//     fragments cover more than its input area, each fragment's area projected onto its input
//     polygon's Newell normal (projected areas add up exactly under splitting and fanning, a bent
//     polygon's pieces' own areas do not); and the split-count identity of BuildStats holds;
//  5. shape: no fragment repeats a vertex (two consecutive vertices within plane_eps) or is a
//     sliver (narrower than plane_eps, is_sliver): shapes the build merges or drops and counts.
// Cost O(sum over fragments of their depth).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "geometry/polygon.h"
#include "tree/tree.h"

namespace bsp {

struct InvariantReport {
  std::uint64_t violations = 0;
  std::vector<std::string> first_problems;  // up to 10, for messages
  bool ok() const { return violations == 0; }
};

// `input` is the polygon list the tree was built from (for the per-source area check).
InvariantReport check_tree_invariants(const Tree& tree, std::span<const Polygon> input);

}  // namespace bsp
