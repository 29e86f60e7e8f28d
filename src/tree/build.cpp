#include "tree/build.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "common/rng.h"
#include "common/tick_clock.h"
#include "tree/build_incremental.h"
#include "tree/build_input.h"
#include "tree/leaf_cell.h"

namespace bsp {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// One pending subtree: its fragments and where to hang the node made from them.
struct WorkItem {
  std::vector<std::uint32_t> ids;
  std::uint32_t parent = kNull;
  bool front_side = true;
  std::uint32_t depth = 1;
  std::uint64_t key = SplitContext::kRootKey;
};

struct Partition {
  std::vector<std::uint32_t> coplanar, front, back;
};

// A subtree built by a task: a tree of its own (nodes, a fragment store, and a plane pool holding
// just the planes it uses), grafted under `parent` once every task is done.
struct Task {
  TreeDraft tree;
  std::unique_ptr<Splitter> splitter;
  WorkItem root;                      // ids in tree.store; parent is kNull inside the task's tree
  std::vector<std::uint32_t> prefix;  // the cell planes above the root, in tree.planes
  // The main pool's index of each of tree.planes' pairs (of the pair's even index) that came from
  // the main pool; pairs past its end are planes the task chose itself.
  std::vector<std::uint32_t> main_index;
  std::uint32_t parent = kNull;       // in the main tree
  bool front_side = true;
};

class RecursiveBuilder {
 public:
  // `prefix`: the cell planes of the path above the first item, root first. `tasks`: where the main
  // builder hands off subtrees of [min_task, max_task] fragments (BuildOptions); null inside a task,
  // which builds everything it is given. The division depends on the input and the options only,
  // never on the thread count, and a splitter's choice depends only on its node's context, so a
  // subtree comes out the same whether a task or the main builder makes it.
  RecursiveBuilder(TreeDraft& tree, Splitter& splitter, const BuildOptions& options, std::vector<std::uint32_t> prefix,
                   std::vector<std::unique_ptr<Task>>* tasks, std::size_t min_task = 0, std::size_t max_task = 0)
      : tree_(tree), store_(tree.store), splitter_(splitter), options_(options), prefix_(std::move(prefix)),
        tasks_(tasks), min_task_(min_task), max_task_(max_task) {}

  void run(WorkItem first) {
    if (first.ids.empty()) return;
    TickBill bill;
    const std::uint64_t store_tests = store_.side_tests();
    std::vector<WorkItem> stack;
    stack.push_back(std::move(first));
    while (!stack.empty()) {
      WorkItem item = std::move(stack.back());
      stack.pop_back();
      const std::size_t m = item.ids.size();
      if (tasks_ && item.parent != kNull && m >= min_task_ && m <= max_task_) {
        hand_off(std::move(item));
        if (store_.vertices_live() < store_.vertex_slots() / 2) compact_store(stack);
      } else {
        process(std::move(item), stack);
      }
    }
    // What the builder spent outside choose and outside the tasks it ran in place (each bills its own).
    const double seconds = bill.close();
    const double choose_seconds = bill.seconds_of(choose_ticks_);
    tree_.stats.machinery_seconds += seconds - choose_seconds - bill.seconds_of(inline_task_ticks_);
    tree_.stats.choose_seconds += choose_seconds;
    tree_.stats.side_tests += store_.side_tests() - store_tests + partition_side_tests_;
    tree_.stats.choose_side_tests += choose_side_tests_;
  }

 private:
  void process(WorkItem item, std::vector<WorkItem>& stack) {
    if (tree_.shape == Shape::Leafy) {
      process_leafy(std::move(item), stack);
      return;
    }
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
    push_children(node, std::move(part), item, stack);
  }

  // A leaf once the fragments bound one convex cell of one group. Otherwise the splitter's plane,
  // unless it leaves every fragment on one side (coplanar ones go the way they face, so even a
  // fragment's own plane can): then the plane of a fragment with another behind it, or, for a
  // convex set of several groups, a free plane between two groups.
  void process_leafy(WorkItem item, std::vector<WorkItem>& stack) {
    const double eps = tree_.tol.plane_eps;
    const auto witness = convexity_witness(item.ids, store_, tree_.planes, eps);
    if (!witness && one_group(item.ids, store_, options_.leaf_groups)) {
      make_node(kNull, item.ids, item);
      return;
    }
    std::uint32_t plane = witness ? choose_plane(item).first : kNull;
    if (plane == kNull || !parts_leafy(item.ids, store_, tree_.planes, tree_.planes[plane], eps)) {
      ++tree_.stats.fallbacks;
      plane = witness ? store_.plane(*witness) : group_plane(item.ids);
    }
    if (plane == kNull) {
      ++tree_.stats.mixed_leaves;  // coincident fragments of two groups, or no separator survived snapping
      make_node(kNull, item.ids, item);
      return;
    }
    Partition part = partition(std::move(item.ids), plane);
    const Vec3 n = tree_.planes[plane].n;
    for (auto id : part.coplanar) (dot(tree_.planes[store_.plane(id)].n, n) > 0 ? part.front : part.back).push_back(id);
    part.coplanar.clear();
    const std::uint32_t node = make_node(plane, {}, item);
    push_children(node, std::move(part), item, stack);
  }

  // The first of group_separators that still parts the set once snapped; kNull when none does.
  std::uint32_t group_plane(const std::vector<std::uint32_t>& ids) {
    for (const Plane& candidate : group_separators(ids, store_, options_.leaf_groups, tree_.tol.plane_eps)) {
      const Plane p = snap(candidate);
      if (parts_leafy(ids, store_, tree_.planes, p, tree_.tol.plane_eps)) return tree_.planes.add(p);
    }
    return kNull;
  }

  Plane snap(const Plane& p) const { return options_.snap_free_plane ? options_.snap_free_plane(p) : p; }

  void push_children(std::uint32_t node, Partition part, const WorkItem& item, std::vector<WorkItem>& stack) {
    if (!part.back.empty())
      stack.push_back({std::move(part.back), node, false, item.depth + 1, SplitContext::child_key(item.key, false)});
    if (!part.front.empty())
      stack.push_back({std::move(part.front), node, true, item.depth + 1, SplitContext::child_key(item.key, true)});
  }

  // Moves the item's fragments, and the planes they and its cell use, into a new task's own store
  // and pool (so the task shares nothing with this builder, which goes on adding fragments and
  // planes, and reuses the space the moved ones leave), then starts it. Runs on the main builder's
  // thread, in its deterministic order.
  void hand_off(WorkItem item) {
    auto& task = *tasks_->emplace_back(std::make_unique<Task>());
    task.tree.shape = tree_.shape;
    task.tree.tol = tree_.tol;
    task.tree.bounds = tree_.bounds;
    task.tree.store = FragmentStore(store_.has_tex_coords());
    task.splitter = splitter_.clone();
    const auto adopt = [&](std::uint32_t p) {
      const std::uint32_t local = task.tree.planes.add(tree_.planes[p]);
      if ((local >> 1) == task.main_index.size()) task.main_index.push_back(p ^ (local & 1u));
      return local;
    };
    collect_cell_planes(item);
    for (auto p : cell_planes_) task.prefix.push_back(adopt(p));
    std::size_t vertices = 0;
    for (auto id : item.ids) vertices += store_.points(id).size();
    task.tree.store.reserve(FragmentStore::kGrowthRoom * item.ids.size(), FragmentStore::kGrowthRoom * vertices);
    std::vector<std::uint32_t> ids;
    ids.reserve(item.ids.size());
    for (auto id : item.ids) {
      ids.push_back(task.tree.store.add(store_.view(id), adopt(store_.plane(id)), store_.sphere(id)));
      store_.release(id);
    }
    task.root = {std::move(ids), kNull, true, item.depth, item.key};
    task.parent = item.parent;
    task.front_side = item.front_side;
    // The task may outlive this builder (a temporary of the single region): it takes what it needs
    // by value, and the options by a pointer into build_tree's caller, which outlives every task.
    Task* t = &task;
    const BuildOptions* options = &options_;
    // The runtime may run the task here, at once (always on one thread): that is the task's time.
    const std::uint64_t start = read_ticks();
#pragma omp task default(none) firstprivate(t, options)
    RecursiveBuilder(t->tree, *t->splitter, *options, std::move(t->prefix), nullptr).run(std::move(t->root));
    inline_task_ticks_ += ticks_since(start);
  }

  // Handed-off fragments leave space the main builder, which makes only the top of the tree, would
  // never fill again: once they are half the store, the store is compacted and every id renamed,
  // so the input's copy does not outlive its hand-off (a linear cost each time the store halves).
  void compact_store(std::vector<WorkItem>& stack) {
    const std::vector<std::uint32_t> to_new = store_.compact();
    for (WorkItem& w : stack)
      for (auto& id : w.ids) id = to_new[id];
    for (auto& id : tree_.fragments) id = to_new[id];
  }

  // The chosen pooled plane, and whether it is the plane of one of the node's fragments.
  std::pair<std::uint32_t, bool> choose_plane(const WorkItem& item) {
    if (splitter_.needs_cell()) collect_cell_planes(item);
    const SplitContext ctx{item.ids, store_, tree_.planes, tree_.tol, tree_.bounds, cell_planes_, item.depth, item.key};
    const std::uint64_t start = read_ticks();
    const std::uint64_t tests = store_.side_tests();
    const SplitChoice choice = splitter_.choose(ctx);
    choose_ticks_ += ticks_since(start);
    choose_side_tests_ += store_.side_tests() - tests;
    switch (choice.kind) {
      case SplitChoice::Kind::Fragment: return {store_.plane(choice.fragment), true};
      case SplitChoice::Kind::Free: return {tree_.planes.add(snap(choice.plane)), false};
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
    cell_planes_.insert(cell_planes_.end(), prefix_.rbegin(), prefix_.rend());
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
      // The spheres are scattered through the store; the ids ahead are known (and not yet
      // overwritten: writes stay at or before r).
      if (r + kPrefetchAhead < size) store_.prefetch_sphere(data[r + kPrefetchAhead]);
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
    partition_side_tests_ += size;
    ids.resize(w);
    part.front = std::move(ids);
    return part;
  }

  // The per-vertex classification of a fragment the sphere test left undecided; returns the new
  // front write position. Writes into the front set stay at or before the read position: a
  // fragment frees one slot and fills at most one.
  std::size_t place_undecided(std::uint32_t id, const Plane& plane, std::uint32_t* front, std::size_t w,
                              Partition& part) {
    partition_side_tests_ += store_.points(id).size();
    switch (classify(store_.points(id), plane, tree_.tol.plane_eps)) {
      case Side::Front: front[w++] = id; break;
      case Side::Back: part.back.push_back(id); break;
      case Side::Coplanar: part.coplanar.push_back(id); break;
      case Side::Spanning: {
        const auto [f, b] = split_fragment(id, plane);
        if (f != FragmentStore::kNone) front[w++] = f;
        if (b != FragmentStore::kNone) part.back.push_back(b);
        break;
      }
    }
    return w;
  }

  // Splits a spanning fragment; returns the ids of its kept front and back parts (kNone if dropped).
  std::pair<std::uint32_t, std::uint32_t> split_fragment(std::uint32_t id, const Plane& plane) {
    const std::uint32_t source = store_.source(id);
    const FragmentStore::Parts r = store_.split(id, plane, tree_.tol.plane_eps);
    if (tree_.log_splits) tree_.split_log.push_back({source, static_cast<std::uint32_t>(r.dropped), r.dropped_area});
    ++tree_.stats.splits;
    tree_.stats.dropped_slivers += r.dropped;
    tree_.stats.dropped_area += r.dropped_area;
    return {r.front, r.back};
  }

  // Appends a node storing `ids` and links it under the item's parent.
  std::uint32_t make_node(std::uint32_t plane, const std::vector<std::uint32_t>& ids, const WorkItem& item) {
    const auto index = static_cast<std::uint32_t>(tree_.nodes.size());
    DraftNode n;
    n.plane = plane;
    n.first = static_cast<std::uint32_t>(tree_.fragments.size());
    n.count = static_cast<std::uint32_t>(ids.size());
    for (auto id : ids) {
      tree_.fragment_plane.push_back(store_.plane(id));
      tree_.fragments.push_back(id);
    }
    tree_.nodes.push_back(n);
    parent_.push_back(item.parent);
    parent_front_.push_back(item.front_side);
    if (item.parent != kNull) (item.front_side ? tree_.nodes[item.parent].front : tree_.nodes[item.parent].back) = index;
    return index;
  }

  TreeDraft& tree_;
  FragmentStore& store_;
  Splitter& splitter_;
  const BuildOptions& options_;
  std::vector<std::uint32_t> prefix_;
  std::vector<std::unique_ptr<Task>>* tasks_;
  std::size_t min_task_, max_task_;
  std::vector<std::uint32_t> cell_planes_;
  std::vector<std::uint32_t> parent_;  // build-time side data, parallel to tree_.nodes
  std::vector<bool> parent_front_;
  // This builder's time inside Splitter::choose, and in task statements (which may run the task in
  // place), in ticks of its TickBill.
  std::uint64_t choose_ticks_ = 0, inline_task_ticks_ = 0;
  std::uint64_t choose_side_tests_ = 0;     // the store's side tests made inside choose
  std::uint64_t partition_side_tests_ = 0;  // partition's own, which bypasses the store's classify
};

// The main pool's index of every plane of a finished task's pool, by pair: the planes the task was
// given map back to where they came from, the ones it chose itself join the main pool (where an
// identical plane meets its twin again).
std::vector<std::uint32_t> planes_to_main(PlanePool& main, Task& task) {
  std::vector<std::uint32_t> to_main = std::move(task.main_index);
  for (auto k = static_cast<std::uint32_t>(to_main.size()); k < task.tree.planes.size() / 2; ++k)
    to_main.push_back(main.add(task.tree.planes[2 * k]));
  return to_main;
}

// Lays the main builder's nodes and the tasks' subtrees out as one tree in pre-order (front child
// first), the order a build without tasks makes, in arrays allocated once at their final size. A
// task's subtree is already in pre-order, so it is copied as one block with its links shifted; its
// fragments stay in the task's store, which joins the draft's task_stores, until freeze() packs
// them: copied once, not twice.
class Assembler {
 public:
  Assembler(TreeDraft& main, std::vector<std::unique_ptr<Task>>& tasks) : main_(main), tasks_(tasks) {}

  void run() {
    hung_.assign(2 * main_.nodes.size(), kNull);
    std::size_t nodes = main_.nodes.size(), fragments = main_.fragments.size();
    for (std::uint32_t t = 0; t < tasks_.size(); ++t) {
      hung_[2 * tasks_[t]->parent + (tasks_[t]->front_side ? 0 : 1)] = t;
      nodes += tasks_[t]->tree.nodes.size();
      fragments += tasks_[t]->tree.fragments.size();
    }
    nodes_.reserve(nodes);
    fragments_.reserve(fragments);
    planes_.reserve(fragments);
    stores_.reserve(fragments);
    main_.task_stores.reserve(tasks_.size());
    std::vector<Pending> stack{{0, false, kNull, true}};
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const auto at = static_cast<std::uint32_t>(nodes_.size());
      if (p.parent != kNull) (p.front_side ? nodes_[p.parent].front : nodes_[p.parent].back) = at;
      if (p.task) copy_task(*tasks_[p.index]);
      else copy_main(p.index, at, stack);
    }
    main_.nodes = std::move(nodes_);
    main_.fragments = std::move(fragments_);
    main_.fragment_plane = std::move(planes_);
    main_.fragment_store = std::move(stores_);
  }

 private:
  // A subtree still to lay out: main node `index`, or task `index`, to link under `parent` (new index).
  struct Pending {
    std::uint32_t index;
    bool task;
    std::uint32_t parent;
    bool front_side;
  };

  void copy_main(std::uint32_t index, std::uint32_t at, std::vector<Pending>& stack) {
    const DraftNode& old = main_.nodes[index];
    DraftNode n = old;
    n.front = n.back = kNull;  // set when the children are laid out
    append_fragments(n, 0, [&](std::uint32_t f) { return std::pair(main_.fragments[f], main_.fragment_plane[f]); });
    nodes_.push_back(n);
    push_child(stack, old.back, hung_[2 * index + 1], at, false);
    push_child(stack, old.front, hung_[2 * index], at, true);
  }

  static void push_child(std::vector<Pending>& stack, std::uint32_t child, std::uint32_t task, std::uint32_t at,
                         bool front) {
    if (child != kNull) stack.push_back({child, false, at, front});
    else if (task != kNull) stack.push_back({task, true, at, front});
  }

  void copy_task(Task& task) {
    const std::vector<std::uint32_t> to_main = planes_to_main(main_.planes, task);
    const auto remap = [&](std::uint32_t p) { return to_main[p >> 1] ^ (p & 1u); };
    const auto offset = static_cast<std::uint32_t>(nodes_.size());
    main_.task_stores.push_back(std::move(task.tree.store));
    const auto store = static_cast<std::uint32_t>(main_.task_stores.size());
    for (DraftNode n : task.tree.nodes) {
      if (n.plane != kNull) n.plane = remap(n.plane);
      if (n.front != kNull) n.front += offset;
      if (n.back != kNull) n.back += offset;
      append_fragments(n, store, [&](std::uint32_t f) {
        return std::pair(task.tree.fragments[f], remap(task.tree.fragment_plane[f]));
      });
      nodes_.push_back(n);
    }
    BuildStats& to = main_.stats;
    const BuildStats& from = task.tree.stats;
    to.splits += from.splits;
    to.dropped_slivers += from.dropped_slivers;
    to.dropped_area += from.dropped_area;
    to.fallbacks += from.fallbacks;
    to.mixed_leaves += from.mixed_leaves;
    to.choose_seconds += from.choose_seconds;
    to.machinery_seconds += from.machinery_seconds;
    to.side_tests += from.side_tests;
    to.choose_side_tests += from.choose_side_tests;
    task = Task{};
  }

  // Appends node n's fragments, (id in `store`, plane) = take(f) for each of its old positions f,
  // and points n at them. `store` as TreeDraft::fragment_store.
  template <class Take>
  void append_fragments(DraftNode& n, std::uint32_t store, Take take) {
    const std::uint32_t first = n.first;
    n.first = static_cast<std::uint32_t>(fragments_.size());
    for (std::uint32_t f = first; f < first + n.count; ++f) {
      const auto [id, plane] = take(f);
      fragments_.push_back(id);
      planes_.push_back(plane);
      stores_.push_back(store);
    }
  }

  TreeDraft& main_;
  std::vector<std::unique_ptr<Task>>& tasks_;
  std::vector<std::uint32_t> hung_;  // per main node and side (2n front, 2n+1 back): the task hung there
  PageVector<DraftNode> nodes_;
  std::vector<std::uint32_t> fragments_;  // ids in the stores of stores_
  std::vector<std::uint32_t> planes_;
  std::vector<std::uint32_t> stores_;  // as TreeDraft::fragment_store
};

// Builds the tree top-down; subtrees handed off run as OpenMP tasks on the other threads while the
// main builder goes on, and are laid out with the main builder's nodes once all are done.
void build_recursive(TreeDraft& tree, Splitter& splitter, std::vector<std::uint32_t> ids, const BuildOptions& options) {
  std::vector<std::unique_ptr<Task>> tasks;
  const std::size_t min_task = std::max<std::size_t>(options.min_task_fragments, 1);
  const std::size_t max_task = tree.stats.n_input / std::max<std::size_t>(options.task_share, 1);
  if (max_task < min_task) {  // no subtree can become a task: no thread team to start and idle
    RecursiveBuilder(tree, splitter, options, {}, nullptr).run(WorkItem{std::move(ids)});
    return;
  }
#pragma omp parallel default(none) shared(tree, splitter, options, ids, tasks, min_task, max_task)
#pragma omp single
  RecursiveBuilder(tree, splitter, options, {}, &tasks, min_task, max_task).run(WorkItem{std::move(ids)});
  tree.stats.tasks = tasks.size();
  if (tasks.empty()) return;
  const auto start = Clock::now();
  Assembler(tree, tasks).run();
  tree.stats.machinery_seconds += seconds_since(start);
}

}  // namespace

Tree build_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options) {
  if (options.incremental && options.shape == Shape::Leafy)
    throw std::invalid_argument("a leafy tree is built recursively, not incrementally");
  const auto start = Clock::now();
  TreeDraft draft;
  draft.shape = options.shape;
  std::vector<std::uint32_t> ids = load_input(input, draft, options.plane_eps_relative);
  if (options.incremental) {
    build_incremental(draft, std::move(ids), splitter, options);
    splitter.check();
    Tree tree = freeze(std::move(draft));
    tree.stats.build_seconds = seconds_since(start);
    return tree;
  }
  const auto builders = Clock::now();
  build_recursive(draft, splitter, std::move(ids), options);
  splitter.check();
  // The builders and the layout have billed their own time; the main thread's waits for tasks are
  // not work. What remains is loading and freezing.
  const double building = seconds_since(builders);
  Tree tree = freeze(std::move(draft));
  tree.stats.build_seconds = seconds_since(start);
  tree.stats.machinery_seconds += tree.stats.build_seconds - building;
  return tree;
}

void build_subtree(TreeDraft& draft, Splitter& splitter, std::vector<std::uint32_t> ids,
                   std::vector<std::uint32_t> cell_prefix, std::uint32_t depth, std::uint64_t key) {
  if (!draft.nodes.empty() || ids.empty())
    throw std::logic_error("build_subtree needs an empty draft and at least one fragment");
  static const BuildOptions kPlain;
  RecursiveBuilder(draft, splitter, kPlain, std::move(cell_prefix), nullptr)
      .run(WorkItem{std::move(ids), kNull, true, depth, key});
  splitter.check();
}

Tree build_incremental_tree(std::span<const Polygon> input, const BuildOptions& options) {
  struct NoSplitter final : Splitter {
    SplitChoice choose(const SplitContext&) override { return SplitChoice::none(); }
    std::unique_ptr<Splitter> clone() const override { return std::make_unique<NoSplitter>(); }
  } none;
  BuildOptions incremental = options;
  incremental.incremental = true;
  return build_tree(input, none, incremental);
}

std::uint64_t insertion_order_seed(std::uint64_t seed) { return stream_seed(seed, 0x04de5); }

}  // namespace bsp
