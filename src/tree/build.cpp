#include "tree/build.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "common/rng.h"
#include "tree/build_incremental.h"
#include "tree/build_input.h"

namespace bsp {

namespace {

// One pending subtree: its fragments and where to hang the node made from them.
struct WorkItem {
  std::vector<std::uint32_t> ids;
  std::uint32_t parent = kNull;
  bool front_side = true;
  std::uint32_t depth = 1;
};

struct Partition {
  std::vector<std::uint32_t> coplanar, front, back;
};

class RecursiveBuilder {
 public:
  RecursiveBuilder(Tree& tree, FragmentStore& store, Splitter& splitter)
      : tree_(tree), store_(store), splitter_(splitter) {}

  void run(std::vector<std::uint32_t> ids) {
    if (ids.empty()) return;
    std::vector<WorkItem> stack;
    stack.push_back({std::move(ids), kNull, true, 1});
    while (!stack.empty()) {
      WorkItem item = std::move(stack.back());
      stack.pop_back();
      process(std::move(item), stack);
    }
  }

 private:
  void process(WorkItem item, std::vector<WorkItem>& stack) {
    if (tree_.shape == Shape::Coarse && is_convex_set(item.ids, store_, tree_.planes, tree_.tol.plane_eps)) {
      make_node(kNull, item.ids, item);
      return;
    }
    auto [plane, own_fragment] = choose_plane(item);
    // A fragment's own plane always takes that fragment; only a free plane can make no progress.
    if (!own_fragment && separates_nothing(item.ids, plane)) {
      // Fall back to the first fragment's own plane, which always takes at least that fragment,
      // so every node makes progress.
      ++tree_.stats.fallbacks;
      plane = store_.plane(item.ids.front());
    }
    Partition part = partition(std::move(item.ids), plane);
    const std::uint32_t node = make_node(plane, part.coplanar, item);
    if (!part.back.empty()) stack.push_back({std::move(part.back), node, false, item.depth + 1});
    if (!part.front.empty()) stack.push_back({std::move(part.front), node, true, item.depth + 1});
  }

  // The chosen pooled plane, and whether it is the plane of one of the node's fragments.
  std::pair<std::uint32_t, bool> choose_plane(const WorkItem& item) {
    if (splitter_.needs_cell()) collect_cell_planes(item);
    const SplitContext ctx{item.ids, store_, tree_.planes, tree_.tol, tree_.bounds, cell_planes_, item.depth};
    const SplitChoice choice = splitter_.choose(ctx);
    switch (choice.kind) {
      case SplitChoice::Kind::Fragment: return {store_.plane(choice.fragment), true};
      case SplitChoice::Kind::Free: return {tree_.planes.add(choice.plane), false};
      case SplitChoice::Kind::None: break;
    }
    return {store_.plane(item.ids.front()), true};
  }

  // True when no fragment is coplanar with the plane and all lie on one side (nothing split).
  bool separates_nothing(const std::vector<std::uint32_t>& ids, std::uint32_t plane_index) const {
    const SideCounts c = store_.count_sides(ids, tree_.planes[plane_index], tree_.tol.plane_eps);
    return c.coplanar == 0 && c.spanning == 0 && (c.front == 0 || c.back == 0);
  }

  // The planes bounding the item's cell, root first; each oriented so the cell is in front.
  void collect_cell_planes(const WorkItem& item) {
    cell_planes_.clear();
    std::uint32_t node = item.parent;
    bool front = item.front_side;
    while (node != kNull) {
      const std::uint32_t p = tree_.nodes[node].plane;
      cell_planes_.push_back(front ? p : PlanePool::flip(p));
      front = parent_front_[node];
      node = parent_[node];
    }
    std::reverse(cell_planes_.begin(), cell_planes_.end());
  }

  // Filters `ids` in place into the front set (the common case keeps most fragments on one side,
  // so this avoids a copy per level); the other sets go to new lists. The bounding-sphere test
  // runs in a tight loop of locals; only undecided fragments take the full per-vertex path.
  Partition partition(std::vector<std::uint32_t> ids, std::uint32_t plane_index) {
    const Plane plane = tree_.planes[plane_index];
    const double eps = tree_.tol.plane_eps;
    Partition part;
    std::uint32_t* data = ids.data();
    const std::size_t size = ids.size();
    std::size_t w = 0;
    for (std::size_t r = 0; r < size; ++r) {
      const std::uint32_t id = data[r];
      const BoundingSphere& s = store_.sphere(id);
      const double d = plane.distance(s.center);
      if (d - s.radius > eps) {
        data[w++] = id;
      } else if (d + s.radius < -eps) {
        part.back.push_back(id);
      } else {
        w = place_undecided(id, plane, data, w, part);
        data = ids.data();
      }
    }
    ids.resize(w);
    part.front = std::move(ids);
    return part;
  }

  // The per-vertex classification of a fragment the sphere test left undecided; returns the new
  // front write position. Writes into the front set stay at or before the read position: a
  // fragment frees one slot and fills at most one.
  std::size_t place_undecided(std::uint32_t id, const Plane& plane, std::uint32_t* front, std::size_t w,
                              Partition& part) {
    switch (classify(store_.poly(id), plane, tree_.tol.plane_eps)) {
      case Side::Front: front[w++] = id; break;
      case Side::Back: part.back.push_back(id); break;
      case Side::Coplanar: part.coplanar.push_back(id); break;
      case Side::Spanning: {
        const auto [f, b] = split_fragment(id, plane);
        if (f != kNull) front[w++] = f;
        if (b != kNull) part.back.push_back(b);
        break;
      }
    }
    return w;
  }

  // Splits a spanning fragment; returns the ids of its kept front and back parts (kNull if dropped).
  std::pair<std::uint32_t, std::uint32_t> split_fragment(std::uint32_t id, const Plane& plane) {
    const std::uint32_t support = store_.plane(id);
    SplitResult r = split(store_.take(id), plane, tree_.tol.plane_eps);
    ++tree_.stats.splits;
    tree_.stats.dropped_slivers += r.dropped;
    tree_.stats.dropped_area += r.dropped_area;
    return {r.front ? store_.add(std::move(*r.front), support) : kNull,
            r.back ? store_.add(std::move(*r.back), support) : kNull};
  }

  // Appends a node storing `ids` and links it under the item's parent.
  std::uint32_t make_node(std::uint32_t plane, const std::vector<std::uint32_t>& ids, const WorkItem& item) {
    const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
    Node n;
    n.plane = plane;
    n.first = static_cast<std::uint32_t>(tree_.fragments.size());
    n.count = static_cast<std::uint32_t>(ids.size());
    for (auto id : ids) {
      tree_.fragment_plane.push_back(store_.plane(id));
      tree_.fragments.push_back(store_.take(id));
    }
    tree_.nodes.push_back(n);
    parent_.push_back(item.parent);
    parent_front_.push_back(item.front_side);
    if (item.parent != kNull) (item.front_side ? tree_.nodes[item.parent].front : tree_.nodes[item.parent].back) = index;
    return index;
  }

  Tree& tree_;
  FragmentStore& store_;
  Splitter& splitter_;
  std::vector<std::uint32_t> cell_planes_;
  std::vector<std::uint32_t> parent_;  // build-time side data, parallel to tree_.nodes
  std::vector<bool> parent_front_;
};

}  // namespace

Tree build_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Tree tree;
  tree.shape = options.shape;
  FragmentStore store;
  std::vector<std::uint32_t> ids = load_input(input, tree, store);
  if (options.incremental)
    build_incremental(tree, store, std::move(ids), splitter, options);
  else
    RecursiveBuilder(tree, store, splitter).run(std::move(ids));
  tree.freeze();
  tree.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

Tree build_incremental_tree(std::span<const Polygon> input, const BuildOptions& options) {
  struct NoSplitter final : Splitter {
    SplitChoice choose(const SplitContext&) override { return SplitChoice::none(); }
  } none;
  BuildOptions incremental = options;
  incremental.incremental = true;
  return build_tree(input, none, incremental);
}

std::uint64_t insertion_order_seed(std::uint64_t seed) { return stream_seed(seed, 0x04de5); }

}  // namespace bsp
