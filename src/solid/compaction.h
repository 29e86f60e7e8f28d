#pragma once
// Compaction of a merge's work array, the compacting half of mark-compact garbage collection
// [Jones2011, ch. 3]. Merging appends every part partitionTree makes to one node array and frees
// none, and a part partitioned again further down the first tree is never referenced again. With a
// chain-shaped operand (an autopartition of a convex solid, as deep as the solid has faces) that
// garbage is quadratic: a 10^4-triangle union made 6.5 M nodes to keep 24 thousand. Compaction
// keeps the made nodes reachable from the merge's live references (the parts still to merge and
// the finished results), in their order, and renumbers every link to them, so the work array holds
// about what is live. The operands' nodes, below `first_made`, never move and link only among
// themselves.
//
// Invariant: the live references the caller passes are all the links into made nodes that the rest
// of the merge will follow; a made node reachable from none of them is never read again.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "solid/solid_tree.h"

namespace bsp {

// When a merge compacts: once it has made at least `floor` nodes and more than twice as many as
// were live after the last compaction, so each compaction's cost, linear in the made nodes, is paid
// for by the nodes made since the last one. Between compactions the work array holds at most
// max(floor, 2 × the nodes live at the last one) made nodes, plus the parts of one merge step.
struct CompactionPolicy {
  std::uint64_t floor = 1u << 18;  // nodes made before the first compaction (a merge that never
                                   // reaches it, most of them, pays nothing)
  bool due(std::uint64_t made, std::uint64_t live_after_last) const {
    return made >= floor && made > 2 * live_after_last;
  }
};

// Keeps the made nodes (index >= first_made) that the references reach, moves them down in index
// order and rewrites every link, the references included. `Node` has Ref front and back; `side`
// is parallel to the nodes (their sub-hyperplanes) and moves with them. Returns how many made
// nodes are live.
template <class Node>
std::uint64_t compact_made_nodes(std::vector<Node>& nodes, std::vector<std::uint32_t>& side, Ref first_made,
                                 std::span<Ref* const> references) {
  constexpr Ref kGarbage = kOut, kLive = kIn;  // marks; step 2 gives each live node its index
  const auto first = static_cast<std::size_t>(first_made);
  const std::size_t made = nodes.size() - first;
  const auto is_made = [&](Ref r) { return !is_leaf(r) && static_cast<std::size_t>(r) >= first; };
  // 1. Mark: what the references reach through made nodes (parts may share unchanged subtrees).
  std::vector<Ref> to(made, kGarbage);
  std::vector<Ref> stack;
  for (Ref* r : references)
    if (is_made(*r)) stack.push_back(*r);
  while (!stack.empty()) {
    const Ref r = stack.back();
    stack.pop_back();
    Ref& mark = to[static_cast<std::size_t>(r) - first];
    if (mark == kLive) continue;
    mark = kLive;
    for (const Ref c : {nodes[static_cast<std::size_t>(r)].front, nodes[static_cast<std::size_t>(r)].back})
      if (is_made(c)) stack.push_back(c);
  }
  // 2. Number the live nodes in index order; moving down in that order overwrites only garbage
  // or nodes already moved.
  Ref next = first_made;
  for (std::size_t i = 0; i < made; ++i)
    if (to[i] == kLive) to[i] = next++;
  const auto moved = [&](Ref r) { return is_made(r) ? to[static_cast<std::size_t>(r) - first] : r; };
  for (std::size_t i = 0; i < made; ++i) {
    if (to[i] == kGarbage) continue;
    Node n = nodes[first + i];
    n.front = moved(n.front);
    n.back = moved(n.back);
    nodes[static_cast<std::size_t>(to[i])] = n;
    side[static_cast<std::size_t>(to[i])] = side[first + i];
  }
  for (Ref* r : references) *r = moved(*r);
  nodes.resize(static_cast<std::size_t>(next));
  side.resize(static_cast<std::size_t>(next));
  return static_cast<std::uint64_t>(next - first_made);
}

// A merge loop's compaction point (merge.cpp, exact_merge.cpp), between two merge steps: the live
// references are the parts of B that the frames still to start will merge (`b` of a frame not yet
// `combining`) and the finished results. `Frame` has Ref b and bool combining.
class Compactor {
 public:
  Compactor(CompactionPolicy policy, Ref first_made) : policy_(policy), first_made_(first_made) {}
  Ref first_made() const { return first_made_; }
  // The made nodes reclaimed, or nothing when no compaction was due.
  template <class Node, class Frame>
  std::optional<std::uint64_t> run_if_due(std::vector<Node>& nodes, std::vector<std::uint32_t>& side,
                                          std::vector<Frame>& frames, std::vector<Ref>& results) {
    const std::uint64_t made = nodes.size() - static_cast<std::size_t>(first_made_);
    if (!policy_.due(made, live_)) return std::nullopt;
    references_.clear();
    for (Frame& f : frames)
      if (!f.combining) references_.push_back(&f.b);
    for (Ref& r : results) references_.push_back(&r);
    live_ = compact_made_nodes(nodes, side, first_made_, references_);
    return made - live_;
  }

 private:
  CompactionPolicy policy_;
  Ref first_made_;
  std::uint64_t live_ = 0;  // after the last compaction
  std::vector<Ref*> references_;
};

}  // namespace bsp
