#include "tree/build_incremental.h"

#include <utility>

#include "common/rng.h"

namespace bsp {

namespace {

// The tree while it grows: node fragment lists are open-ended until freeze().
class IncrementalBuilder {
 public:
  explicit IncrementalBuilder(TreeDraft& tree) : tree_(tree), store_(tree.store) {}

  void insert(std::uint32_t id) {
    if (nodes_.empty()) {
      new_node(id);
      return;
    }
    pending_.push_back({id, 0});
    while (!pending_.empty()) {
      auto [f, n] = pending_.back();
      pending_.pop_back();
      descend(f, n);
    }
  }

  // Moves the fragments into the tree, nodes in pre-order (front child first).
  void freeze() {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;  // (scratch node, parent slot)
    if (!nodes_.empty()) stack.push_back({0, kNull});
    while (!stack.empty()) {
      auto [s, parent] = stack.back();
      stack.pop_back();
      const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
      DraftNode n;
      n.plane = nodes_[s].plane;
      n.first = static_cast<std::uint32_t>(tree_.fragments.size());
      n.count = static_cast<std::uint32_t>(frags_[s].size());
      for (auto id : frags_[s]) {
        tree_.fragment_plane.push_back(store_.plane(id));
        tree_.fragments.push_back(id);
      }
      tree_.nodes.push_back(n);
      if (parent != kNull) {
        const bool is_front = nodes_[parent_scratch_[s]].front == s;
        (is_front ? tree_.nodes[parent].front : tree_.nodes[parent].back) = index;
      }
      if (nodes_[s].back != kNull) stack.push_back({nodes_[s].back, index});
      if (nodes_[s].front != kNull) stack.push_back({nodes_[s].front, index});
    }
  }

 private:
  void descend(std::uint32_t f, std::uint32_t n) {
    if (nodes_[n].plane == kNull) {
      add_to_leaf(f, n);
      return;
    }
    const Plane& plane = tree_.planes[nodes_[n].plane];
    switch (store_.classify(f, plane, tree_.tol.plane_eps)) {
      case Side::Coplanar: frags_[n].push_back(f); break;
      case Side::Front: go(f, n, true); break;
      case Side::Back: go(f, n, false); break;
      case Side::Spanning: {
        const FragmentStore::Parts r = store_.split(f, plane, tree_.tol.plane_eps);
        ++tree_.stats.splits;
        tree_.stats.dropped_slivers += r.dropped;
        tree_.stats.dropped_area += r.dropped_area;
        if (r.back != FragmentStore::kNone) go(r.back, n, false);
        if (r.front != FragmentStore::kNone) go(r.front, n, true);
        break;
      }
    }
  }

  void go(std::uint32_t f, std::uint32_t n, bool front) {
    const std::uint32_t child = front ? nodes_[n].front : nodes_[n].back;
    if (child != kNull) {
      pending_.push_back({f, child});
      return;
    }
    const std::uint32_t made = new_node(f);
    (front ? nodes_[n].front : nodes_[n].back) = made;
    parent_scratch_[made] = n;
  }

  std::uint32_t new_node(std::uint32_t f) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    DraftNode n;
    n.plane = tree_.shape == Shape::Coarse ? kNull : store_.plane(f);
    nodes_.push_back(n);
    frags_.push_back({f});
    parent_scratch_.push_back(kNull);
    return index;
  }

  // The leaf already holds a convex set, so it stays one iff the newcomer and each member lie in
  // front of or on each other's planes: O(k) instead of re-checking all pairs.
  bool keeps_convex(std::uint32_t f, const std::vector<std::uint32_t>& leaf) const {
    const double eps = tree_.tol.plane_eps;
    const Plane& pf = tree_.planes[store_.plane(f)];
    for (auto g : leaf)
      if (!in_front_or_on(store_.points(g), pf, eps) ||
          !in_front_or_on(store_.points(f), tree_.planes[store_.plane(g)], eps))
        return false;
    return true;
  }

  // Coarse leaves only: keep the convex set, or split the leaf on the newcomer's plane.
  void add_to_leaf(std::uint32_t f, std::uint32_t n) {
    if (keeps_convex(f, frags_[n])) {
      frags_[n].push_back(f);
      return;
    }
    std::vector<std::uint32_t> old = std::move(frags_[n]);
    frags_[n] = {};
    nodes_[n].plane = store_.plane(f);
    pending_.push_back({f, n});
    for (auto it = old.rbegin(); it != old.rend(); ++it) pending_.push_back({*it, n});
  }

  TreeDraft& tree_;
  FragmentStore& store_;
  std::vector<DraftNode> nodes_;  // scratch; first/count unused until freeze()
  std::vector<std::vector<std::uint32_t>> frags_;
  std::vector<std::uint32_t> parent_scratch_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pending_;  // (fragment, node) to descend
};

void shuffle(std::vector<std::uint32_t>& ids, std::uint64_t seed) {
  Rng rng(seed);
  for (std::size_t i = ids.size(); i > 1; --i) std::swap(ids[i - 1], ids[rng.below(i)]);
}

}  // namespace

void build_incremental(TreeDraft& tree, std::vector<std::uint32_t> ids, Splitter&, const BuildOptions& options) {
  if (options.order == InsertOrder::Shuffled) shuffle(ids, options.order_seed);
  IncrementalBuilder builder(tree);
  const std::uint64_t tests = tree.store.side_tests();
  for (auto id : ids) builder.insert(id);
  tree.stats.side_tests += tree.store.side_tests() - tests;  // every one of them a descent's classification
  builder.freeze();
}

}  // namespace bsp
