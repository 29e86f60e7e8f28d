#include "tree/exact_build.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "common/tick_clock.h"

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

// A node as built: its pooled plane (kNull for a coarse leaf) and how many fragments it holds.
struct BuiltNode {
  std::uint32_t plane = kNull, front = kNull, back = kNull;
  std::uint32_t fragments = 0;
};

// What the build produces: its nodes in pre-order and their fragments in node order, each taken
// out of the store with its pooled plane when its node is made.
struct Built {
  std::vector<BuiltNode> nodes;
  PlanePolygonSet fragments;                  // by reference into the store's input planes and the pool
  std::vector<std::uint32_t> fragment_plane;  // pooled
};

class ExactBuilder {
 public:
  ExactBuilder(ExactFragments& frags, Splitter& splitter, Shape shape, Tolerance tol, Box bounds, BuildStats& stats,
               ExactBuildStats& exact)
      : frags_(frags), splitter_(splitter), shape_(shape), tol_(tol), bounds_(bounds), stats_(stats), exact_(exact) {}

  Built run(std::vector<std::uint32_t> ids) {
    TickBill bill;
    std::vector<WorkItem> stack;
    if (!ids.empty()) stack.push_back({std::move(ids)});
    while (!stack.empty()) {
      WorkItem item = std::move(stack.back());
      stack.pop_back();
      process(std::move(item), stack);
    }
    bill.close();
    stats_.choose_seconds += bill.seconds_of(choose_ticks_);
    return std::move(built_);
  }

 private:
  void process(WorkItem item, std::vector<WorkItem>& stack) {
    if (shape_ == Shape::Coarse && convex_set(item.ids)) {
      make_node(kNull, item.ids, item);
      return;
    }
    auto [plane, own_fragment] = choose_plane(item);
    if (!own_fragment && separates_nothing(item.ids, plane)) {
      ++stats_.fallbacks;  // the first fragment's own plane takes at least that fragment
      plane = frags_.plane(item.ids.front());
    }
    Partition part = partition(std::move(item.ids), plane);
    const std::uint32_t node = make_node(plane, part.coplanar, item);
    if (!part.back.empty()) stack.push_back({std::move(part.back), node, false, item.depth + 1, SplitContext::child_key(item.key, false)});
    if (!part.front.empty()) stack.push_back({std::move(part.front), node, true, item.depth + 1, SplitContext::child_key(item.key, true)});
  }

  // IS-CONVEX-SET [DividingPolygon], decided exactly.
  bool convex_set(const std::vector<std::uint32_t>& ids) const {
    for (auto a : ids)
      for (auto b : ids) {
        if (a == b) continue;
        const Side s = frags_.classify(a, frags_.plane(b));
        if (s != Side::Front && s != Side::Coplanar) return false;
      }
    return true;
  }

  std::pair<std::uint32_t, bool> choose_plane(const WorkItem& item) {
    if (splitter_.needs_cell()) collect_cell_planes(item);
    SplitContext ctx{item.ids, frags_.rounded(), frags_.planes().scene_planes(), tol_, bounds_, cell_planes_,
                     item.depth, item.key};
    ctx.exact = &frags_;
    const std::uint64_t start = read_ticks();
    const SplitChoice choice = splitter_.choose(ctx);
    choose_ticks_ += ticks_since(start);
    switch (choice.kind) {
      case SplitChoice::Kind::Fragment: return {frags_.plane(choice.fragment), true};
      case SplitChoice::Kind::Free:
        if (const auto rounded = round_plane(choice.plane, frags_.planes().grid())) {
          ++exact_.free_planes;
          return {frags_.planes().add(*rounded), false};
        }
        ++exact_.free_planes_beyond;
        break;
      case SplitChoice::Kind::None: break;
    }
    return {frags_.plane(item.ids.front()), true};
  }

  bool separates_nothing(const std::vector<std::uint32_t>& ids, std::uint32_t plane) const {
    SideCounts c;
    frags_.count_sides(ids, std::span<const std::uint32_t>(&plane, 1), std::span<SideCounts>(&c, 1));
    return c.coplanar == 0 && c.spanning == 0 && (c.front == 0 || c.back == 0);
  }

  void collect_cell_planes(const WorkItem& item) {
    cell_planes_.clear();
    std::uint32_t node = item.parent;
    bool front = item.front_side;
    while (node != kNull) {
      const std::uint32_t p = built_.nodes[node].plane;
      cell_planes_.push_back(front ? p : PlanePool::flip(p));
      front = parent_front_[node];
      node = parent_[node];
    }
    std::reverse(cell_planes_.begin(), cell_planes_.end());
  }

  Partition partition(std::vector<std::uint32_t> ids, std::uint32_t plane) {
    Partition part;
    for (auto id : ids) switch (frags_.classify(id, plane)) {
        case Side::Front: part.front.push_back(id); break;
        case Side::Back: part.back.push_back(id); break;
        case Side::Coplanar: part.coplanar.push_back(id); break;
        case Side::Spanning: {
          const ExactFragments::Parts p = frags_.split(id, plane);
          ++stats_.splits;
          part.front.push_back(p.front);
          part.back.push_back(p.back);
          break;
        }
      }
    return part;
  }

  // The node's fragments leave the store now, while partition has their records in cache: they are
  // final, and nodes are made in the frozen tree's order.
  std::uint32_t make_node(std::uint32_t plane, const std::vector<std::uint32_t>& ids, const WorkItem& item) {
    const auto index = static_cast<std::uint32_t>(built_.nodes.size());
    built_.nodes.push_back({plane, kNull, kNull, static_cast<std::uint32_t>(ids.size())});
    for (auto id : ids) {
      built_.fragment_plane.push_back(frags_.plane(id));
      frags_.take_into(id, built_.fragments);
    }
    parent_.push_back(item.parent);
    parent_front_.push_back(item.front_side);
    if (item.parent != kNull) (item.front_side ? built_.nodes[item.parent].front : built_.nodes[item.parent].back) = index;
    return index;
  }

  ExactFragments& frags_;
  Splitter& splitter_;
  Shape shape_;
  Tolerance tol_;
  Box bounds_;
  BuildStats& stats_;
  ExactBuildStats& exact_;
  Built built_;  // nodes in pre-order (front child first): the stack pops the front first
  std::vector<std::uint32_t> parent_;
  std::vector<bool> parent_front_;
  std::vector<std::uint32_t> cell_planes_;
  std::uint64_t choose_ticks_ = 0;  // time inside Splitter::choose, in ticks of run's TickBill
};

// The frozen tree: planes renumbered in first-use order (nodes, then fragments), as freeze() does
// for a float build, with the grid planes beside them, and the fragments' plane polygons in node
// order. The view's vertices are left for make_view.
void freeze_exact(Built& built, ExactFragments& frags, ExactTree& out) {
  GridPlanePool& pool = frags.planes();
  std::vector<std::uint32_t> pair(pool.size() / 2, kNull);
  const auto remap = [&](std::uint32_t p) {
    std::uint32_t& to = pair[p >> 1];
    if (to == kNull) {
      to = out.tree.planes.append_distinct(pool.scene_planes()[p & ~1u]);
      out.planes.push_back(pool[p & ~1u]);
    }
    return to | (p & 1u);
  };
  out.tree.nodes.reserve(built.nodes.size());
  std::uint32_t first = 0;
  for (const BuiltNode& n : built.nodes) {
    out.tree.nodes.push_back({n.plane == kNull ? kNull : remap(n.plane), n.front, n.back, first});
    first += n.fragments;
  }
  out.tree.fragment_plane.reserve(first);
  for (auto p : built.fragment_plane) out.tree.fragment_plane.push_back(remap(p));
  out.fragments = std::move(built.fragments);
  out.fragments.adopt(frags.release_input_planes(), pool.release_planes());
}

// The view's fragments: each vertex computed from its three planes (vertex_position), the one
// place the exact kernel makes output coordinates (splitters' rounded copies are estimates:
// split/exact_fragments.h).
void make_view(ExactTree& out) {
  out.tree.fragments.reserve(out.fragments.size(), 4 * out.fragments.size());
  Polygon poly;
  for (std::size_t i = 0; i < out.fragments.size(); ++i) {
    const PlanePolygon f = out.fragments[i];
    poly.source = f.source;
    poly.verts.clear();
    for (const Vec3& p : vertex_positions(f, out.grid)) poly.verts.push_back({p});
    out.tree.fragments.push_back(poly);
  }
}

}  // namespace

const char* kernel_name(Kernel k) { return k == Kernel::Exact ? "exact" : "float"; }

std::optional<Kernel> kernel_named(std::string_view name) {
  if (name == "float") return Kernel::Float;
  if (name == "exact") return Kernel::Exact;
  return std::nullopt;
}

ExactTree build_exact_tree(std::span<const Polygon> input, Splitter& splitter, const BuildOptions& options,
                           const Grid* grid) {
  if (options.incremental || options.shape == Shape::Leafy)
    throw std::invalid_argument("the exact kernel builds strict and coarse trees recursively");
  const auto start = Clock::now();
  SnappedScene snapped = grid ? snap_polygons(input, *grid) : snap_polygons(input);
  const double snap_seconds = seconds_since(start);
  ExactTree out;
  out.exact.snap_seconds = snap_seconds;
  out.grid = snapped.grid;
  out.exact.snap = snapped.report;
  Tree& tree = out.tree;
  tree.shape = options.shape;
  for (const Polygon& p : input)
    for (const Vertex& v : p.verts) tree.bounds.add(v.p);
  tree.tol = Tolerance::for_extent(tree.bounds.diagonal());
  BuildStats& stats = tree.stats;
  stats.n_input = input.size();
  stats.dropped_input = snapped.report.not_polygons + snapped.report.degenerate;
  stats.triangulated_extra = snapped.report.fan_triangles - snapped.report.fanned;
  for (const Polygon& p : input) stats.input_area += area(p);
  stats.dropped_area = snapped.report.degenerate_area;

  const auto load = Clock::now();
  GridPlanePool pool(snapped.grid);
  pool.reserve(snapped.polygons.size());
  ExactFragments frags(pool);
  std::size_t vertices = 0;
  for (const PlanePolygon& p : snapped.polygons) vertices += p.size();
  frags.reserve(FragmentStore::kGrowthRoom * snapped.polygons.size(), FragmentStore::kGrowthRoom * vertices,
                snapped.polygons.size(), vertices);
  std::vector<std::uint32_t> ids;
  ids.reserve(snapped.polygons.size());
  for (std::size_t i = 0; i < snapped.polygons.size(); ++i) ids.push_back(frags.add(snapped.polygons[i], snapped.corners[i]));
  snapped.polygons = {};
  snapped.corners = {};
  out.exact.load_seconds = seconds_since(load);

  Built built = ExactBuilder(frags, splitter, options.shape, tree.tol, tree.bounds, stats, out.exact).run(std::move(ids));
  splitter.check();
  freeze_exact(built, frags, out);
  out.exact.sides = frags.counters();
  stats.build_seconds = seconds_since(start);
  stats.machinery_seconds = stats.build_seconds - stats.choose_seconds;
  const auto view = Clock::now();
  make_view(out);
  out.exact.view_seconds = seconds_since(view);
  return out;
}

}  // namespace bsp
