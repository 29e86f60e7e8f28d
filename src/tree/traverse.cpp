#include "tree/traverse.h"

namespace bsp {

namespace {

// a if `take`, else b, by masking. The sweep's conditions (whether a node has a child, which side
// of it the eye is on) vary from node to node without a pattern, and a mispredicted branch costs
// about as much as the rest of a node's work; compilers turn a conditional expression into a
// branch as often as not, but not this.
std::uint32_t pick(bool take, std::uint32_t a, std::uint32_t b) {
  const std::uint32_t mask = 0u - static_cast<std::uint32_t>(take);
  return (a & mask) | (b & ~mask);
}

}  // namespace

namespace detail {

std::optional<TraversalCounters> sweep_order(const Tree& tree, const Vec3& eye, Order order, std::uint32_t* out) {
  const auto n = static_cast<std::uint32_t>(tree.nodes.size());
  const auto total = static_cast<std::uint32_t>(tree.fragments.size());
  const Node* nodes = tree.nodes.data();
  const double eps = tree.tol.plane_eps;
  // A subtree still to place: its root node, its fragments [begin, end) and where its slice of the
  // output starts. The root's index and fragment range are what pre-order predicts; each node is
  // checked against them, so a tree not laid out in pre-order is refused before anything is
  // written outside its slice.
  struct Slice {
    std::uint32_t node, begin, end, out;
  };
  // Back subtrees whose nodes come after the current front subtree, nearest on top; grown by
  // hand so the loop keeps its top in a register instead of a vector's end pointer in memory.
  std::vector<Slice> pending(64);
  std::size_t top = 0;
  Slice cur{0, 0, total, 0};  // the subtree rooted at node i
  std::uint64_t leaves = 0, leaf_evals = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Node& node = nodes[i];
    // The reads away from the sweep, started early: the node's plane in the pool (split parts
    // reuse their source's plane, far away in node order) and where its back subtree's fragments begin.
    constexpr std::uint32_t kAhead = 16;
    if (i + kAhead < n) {
      const std::uint32_t back = nodes[i + kAhead].back;
      __builtin_prefetch(nodes + pick(back < n, back, i));
      const std::uint32_t plane = nodes[i + kAhead].plane;
      tree.planes.prefetch(pick(plane != kNull, plane, 0));
    }
    const std::uint32_t own_end = i + 1 < n ? nodes[i + 1].first : total;
    const bool has_front = node.front != kNull, has_back = node.back != kNull;
    // One branch, never taken for a tree in pre-order: the node is the one pre-order predicts, its
    // fragments begin where its subtree's do, and its children are where pre-order puts them.
    const bool back_valid = has_back & (node.back > i) & (node.back < n);
    const std::uint32_t back_begin = pick(back_valid, nodes[pick(back_valid, node.back, i)].first, cur.end);
    const bool misplaced = (cur.node != i) | (node.first != cur.begin) | (own_end < node.first) |
                           (back_begin < own_end) | (back_begin > cur.end) | (has_back & !back_valid) |
                           (has_front & (node.front != i + 1)) | (!has_front & (back_begin != own_end));
    if (misplaced) [[unlikely]] return std::nullopt;
    Slice front{};
    if (node.is_cell_leaf()) {
      if (has_front || has_back) return std::nullopt;
      ++leaves;
      std::uint32_t* at = out + cur.out;
      TraversalCounters leaf;
      emit_convex_leaf(tree, i, eye, order, [&](std::uint32_t f) { *at++ = f; }, leaf);
      leaf_evals += leaf.plane_evals;
    } else {
      const bool back_first = (tree.planes[node.plane].distance(eye) >= -eps) == (order == Order::BackToFront);
      // The front subtree's fragments follow the node's own and end where the back subtree's begin.
      const std::uint32_t far_size = pick(back_first, cur.end - back_begin, back_begin - own_end);
      std::uint32_t at = cur.out + far_size;
      for (std::uint32_t f = node.first; f < own_end; ++f) out[at++] = f;
      if (top + 1 >= pending.size()) pending.resize(2 * pending.size());
      pending[top] = {node.back, back_begin, cur.end, pick(back_first, cur.out, at)};
      top += has_back;
      front = {i + 1, own_end, back_begin, pick(back_first, at, cur.out)};
    }
    // The next node is the front child, or else (pre-order) the root of the nearest pending back
    // subtree, or there is none.
    const bool pop = !has_front && top > 0;
    const Slice& popped = pending[top - (top > 0)];
    cur = {pick(has_front, front.node, pick(pop, popped.node, kNull)),
           pick(has_front, front.begin, pick(pop, popped.begin, cur.begin)),
           pick(has_front, front.end, pick(pop, popped.end, cur.end)),
           pick(has_front, front.out, pick(pop, popped.out, cur.out))};
    top -= pop;
  }
  // Every subtree placed, every fragment in one: then each fragment was written exactly once.
  if (n == 0 ? total != 0 : (top != 0 || cur.node != kNull)) return std::nullopt;
  TraversalCounters c;
  c.nodes_visited = n;
  c.plane_evals = (n - leaves) + leaf_evals;
  c.fragments_emitted = total;
  return c;
}

}  // namespace detail

TraversalCounters visibility_order(const Tree& tree, const Vec3& eye, Order order, std::vector<std::uint32_t>& out) {
  out.resize(tree.fragments.size());
  if (const auto c = detail::sweep_order(tree, eye, order, out.data())) return *c;
  // A tree not in pre-order: only one a caller rearranged by hand (a test corrupting a tree for a
  // checker to catch), since every builder lays its nodes out so. The walk orders any tree whose
  // child indices are in range and acyclic, as it always required.
  out.clear();
  auto collect = [&](std::uint32_t f) { out.push_back(f); };
  return detail::walk(tree, eye, order, collect, [](const Plane&, TraversalCounters&) { return detail::Visit::Both; });
}

std::vector<std::uint32_t> visibility_order(const Tree& tree, const Vec3& eye, Order order,
                                            TraversalCounters* counters) {
  std::vector<std::uint32_t> out;
  const TraversalCounters c = visibility_order(tree, eye, order, out);
  if (counters) *counters = c;
  return out;
}

}  // namespace bsp
