#pragma once
// What every exact-kernel tree must satisfy, decided exactly (no tolerance anywhere):
//  1. structure: every node is reached from the root once, in pre-order (front child first), and
//     the fragment ranges partition the fragments;
//  2. separation: every vertex of every fragment in a node's front subtree is in front of or on
//     the node's plane, every one in its back subtree behind or on it (side_of_vertex);
//  3. storage: a strict node's fragments have its plane as their support, in either orientation
//     (equality of canonical grid planes); a coarse leaf's fragments are a convex set;
//  4. shape: every fragment is a valid plane polygon (is_valid: defined vertices, counter-clockwise,
//     no zero-length edge), so nothing the build made is a sliver;
//  5. bookkeeping: fragments = usable inputs + splits (nothing dropped after snapping), from the
//     build's own counters.
// Cost O(sum over fragments of depth * vertices) predicates, O(nodes) memory. A tree whose structure
// is broken (a cycle, a child out of range) is reported at its first structural fault and not walked.
#include <cstdint>
#include <string>
#include <vector>

#include "tree/exact_build.h"

namespace bsp {

struct ExactInvariantReport {
  std::uint64_t violations = 0;
  std::vector<std::string> first_problems;  // up to 10
  PredicateCounters predicates;             // how the checker's own tests were decided
  bool ok() const { return violations == 0; }
};

ExactInvariantReport check_exact_invariants(const ExactTree& tree);

}  // namespace bsp
