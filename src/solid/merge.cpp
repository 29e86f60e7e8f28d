#include "solid/merge.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "geometry/convex_loop.h"
#include "geometry/polygon.h"
#include "geometry/polytope.h"
#include "solid/compaction.h"

namespace bsp {

std::string_view set_op_name(SetOp op) {
  switch (op) {
    case SetOp::Union: return "union";
    case SetOp::Intersection: return "intersection";
    case SetOp::Difference: return "difference";
    case SetOp::SymmetricDifference: return "xor";
  }
  return "?";
}

SetOp parse_set_op(std::string_view name) {
  for (SetOp op : {SetOp::Union, SetOp::Intersection, SetOp::Difference, SetOp::SymmetricDifference})
    if (set_op_name(op) == name) return op;
  throw UsageError("unknown set operation '" + std::string(name) + "' (union, intersection, difference, xor)");
}

CellTable cell_table(SetOp op) {
  using C = CellResult;
  switch (op) {
    case SetOp::Union: return {{C::Tree, C::In}, {C::Tree, C::In}};
    case SetOp::Intersection: return {{C::Out, C::Tree}, {C::Out, C::Tree}};
    // A - B: an OUT cell of A stays OUT; an IN cell keeps what B does not hold. A's tree with a
    // cell of B: what B holds is removed.
    case SetOp::Difference: return {{C::Out, C::Complement}, {C::Tree, C::Out}};
    case SetOp::SymmetricDifference: return {{C::Tree, C::Complement}, {C::Tree, C::Complement}};
  }
  return {};
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Both operands and everything the merge makes, in one node array: A's nodes keep their indices,
// B's follow them.
SolidTree combined(const SolidTree& a, const SolidTree& b, Ref& b_root) {
  SolidTree w = a;
  const Ref node_offset = static_cast<Ref>(a.nodes.size());
  const auto loop_offset = static_cast<std::uint32_t>(a.loops.size());
  for (std::size_t i = 0; i < b.nodes.size(); ++i) {
    SolidNode n = b.nodes[i];
    if (!is_leaf(n.front)) n.front += node_offset;
    if (!is_leaf(n.back)) n.back += node_offset;
    w.nodes.push_back(n);
    w.shp.push_back(b.shp[i] + loop_offset);
  }
  for (std::size_t i = 0; i < b.loops.size(); ++i) w.loops.add(b.loops[static_cast<std::uint32_t>(i)]);
  b_root = is_leaf(b.root) ? b.root : b.root + node_offset;
  return w;
}

// The loops of the made nodes that compaction kept, moved down in id order as the nodes were; the
// pieces of shp(t1) partitioning cut, and the loops of garbage nodes, go.
void compact_made_loops(SolidTree& w, Ref first_made, std::uint32_t first_made_loop) {
  constexpr std::uint32_t kGone = 0xffffffffu;
  const std::size_t made = w.loops.size() - first_made_loop;
  std::vector<std::uint32_t> to(made, kGone);
  for (std::size_t i = static_cast<std::size_t>(first_made); i < w.nodes.size(); ++i)
    if (w.shp[i] >= first_made_loop) to[w.shp[i] - first_made_loop] = 0;
  std::vector<Vec3>& points = w.loops.points;
  std::vector<std::uint32_t>& start = w.loops.start;
  std::uint32_t next = first_made_loop, point = start[first_made_loop];
  for (std::uint32_t i = 0; i < made; ++i) {
    if (to[i] == kGone) continue;
    // start[id] and start[id + 1] are read before start[next <= id] is written.
    const std::uint32_t begin = start[first_made_loop + i], end = start[first_made_loop + i + 1];
    if (point != begin) std::copy(points.begin() + begin, points.begin() + end, points.begin() + point);
    start[next] = point;
    point += end - begin;
    to[i] = next++;
  }
  start[next] = point;
  start.resize(next + 1);
  points.resize(point);
  for (std::size_t i = static_cast<std::size_t>(first_made); i < w.nodes.size(); ++i)
    if (w.shp[i] >= first_made_loop) w.shp[i] = to[w.shp[i] - first_made_loop];
}

class Merger {
 public:
  Merger(SolidTree& work, const CellTable& table, MergeStats& stats, MergeOptions options, Ref first_b)
      : w_(work), table_(table), stats_(stats), partitioner_(work, stats, options, first_b),
        compactor_(options.compaction, static_cast<Ref>(work.nodes.size())),
        first_made_loop_(static_cast<std::uint32_t>(work.loops.size())) {}

  Ref merge(Ref a_root, Ref b_root);

 private:
  struct Frame {
    Ref a, b;
    bool combining;  // b is partitioned: waiting for the children's results
  };
  void compact_if_due(std::vector<Frame>& frames, std::vector<Ref>& results);
  Ref cell_op(Ref a, Ref b);
  Ref complement(Ref t);

  SolidTree& w_;
  const CellTable& table_;
  MergeStats& stats_;
  Partitioner partitioner_;
  Compactor compactor_;
  const std::uint32_t first_made_loop_;
};

// Nodes, then their loops; the boxes of the nodes that moved are recomputed when asked for.
void Merger::compact_if_due(std::vector<Frame>& frames, std::vector<Ref>& results) {
  const std::optional<std::uint64_t> reclaimed = compactor_.run_if_due(w_.nodes, w_.shp, frames, results);
  if (!reclaimed) return;
  compact_made_loops(w_, compactor_.first_made(), first_made_loop_);
  partitioner_.forget_boxes_from(compactor_.first_made());
  ++stats_.compactions;
  stats_.compacted_nodes += *reclaimed;
}

Ref Merger::merge(Ref a_root, Ref b_root) {
  std::vector<Frame> frames{{a_root, b_root, false}};
  std::vector<Ref> results;
  while (!frames.empty()) {
    compact_if_due(frames, results);
    const Frame f = frames.back();
    if (!f.combining) {
      if (is_leaf(f.a) || is_leaf(f.b)) {
        results.push_back(cell_op(f.a, f.b));
        frames.pop_back();
        continue;
      }
      ++stats_.merge_nodes;
      const SolidNode na = w_.nodes[f.a];
      const Partitioner::Parts p = partitioner_.partition(f.b, w_.shp[f.a], na.plane);
      frames.back().combining = true;
      frames.push_back({na.back, p.minus, false});
      frames.push_back({na.front, p.plus, false});
      continue;
    }
    const Ref back = results.back();
    results.pop_back();
    const Ref front = results.back();
    results.pop_back();
    const SolidNode na = w_.nodes[f.a];
    // Two children of one leaf are that leaf, as reduce() would make them.
    results.push_back(is_leaf(front) && front == back ? front : w_.add_node(na.plane, w_.shp[f.a], front, back));
    frames.pop_back();
  }
  return results.back();
}

Ref Merger::cell_op(Ref a, Ref b) {
  ++stats_.cell_ops;
  const bool a_is_cell = is_leaf(a);
  const CellResult r = a_is_cell ? table_.first_leaf[a == kIn] : table_.second_leaf[b == kIn];
  const Ref tree = a_is_cell ? b : a;
  switch (r) {
    case CellResult::Out: return kOut;
    case CellResult::In: return kIn;
    case CellResult::Tree: return tree;
    case CellResult::Complement: return complement(tree);
  }
  return kOut;
}

// A copy of the subtree with its leaves flipped (the original may be part of the other side).
Ref Merger::complement(Ref t) {
  if (is_leaf(t)) return flip_label(t);
  const auto copy = [&](Ref from) {
    ++stats_.complement_nodes;
    const SolidNode n = w_.nodes[from];
    return w_.add_node(n.plane, w_.shp[from], n.front, n.back);
  };
  const Ref root = copy(t);
  std::vector<Ref> stack{root};
  while (!stack.empty()) {
    const Ref v = stack.back();
    stack.pop_back();
    for (const bool front : {true, false}) {
      const Ref c = w_.nodes[v].child(front);
      const Ref replaced = is_leaf(c) ? flip_label(c) : copy(c);
      (front ? w_.nodes[v].front : w_.nodes[v].back) = replaced;
      if (!is_leaf(c)) stack.push_back(replaced);
    }
  }
  return root;
}

// Stores the nodes reachable from `root` in pre-order into a new tree. `resolve` maps each link
// to what replaces it (a leaf, another node, or itself); `path` is the chain of half-spaces from
// the root that the link's region lies in.
template <class Resolve>
SolidTree emit_preorder(const SolidTree& src, Ref root, Resolve resolve) {
  SolidTree out;
  out.box = src.box;
  out.tol = src.tol;
  struct Item {
    Ref from;
    Ref parent;  // index in out, or -1 for the root
    bool front;
    std::uint32_t depth;
    Plane towards;
  };
  std::vector<Item> stack{{root, -1, true, 0, {}}};
  std::vector<Plane> path;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    path.resize(item.depth);
    if (item.depth > 0) path.back() = item.towards;
    const Ref r = resolve(item.from, path);
    Ref placed = r;
    if (!is_leaf(r)) {
      const SolidNode& n = src.nodes[r];
      placed = out.add_node(n.plane, out.loops.add(src.loops[src.shp[r]]), kOut, kOut);
      stack.push_back({n.back, placed, false, item.depth + 1, n.plane.flipped()});
      stack.push_back({n.front, placed, true, item.depth + 1, n.plane});
    }
    if (item.parent < 0)
      out.root = placed;
    else
      (item.front ? out.nodes[item.parent].front : out.nodes[item.parent].back) = placed;
  }
  return out;
}

// Which side of node v's plane its region lies on, when shp(v) is empty: the box cut along the path.
// Both when the cut region still crosses the plane by more than plane_eps (the node then stays).
enum class RegionSide : std::uint8_t { Front, Back, Both };
RegionSide region_side(const SolidTree& s, Ref v, const std::vector<Plane>& path) {
  ConvexPolytope cell = ConvexPolytope::box(s.box);
  for (const Plane& p : path) cell = cell.clipped(p, s.tol.plane_eps);
  const Plane& h = s.nodes[v].plane;
  const bool front = !cell.clipped(h, s.tol.plane_eps).empty();
  const bool back = !cell.clipped(h.flipped(), s.tol.plane_eps).empty();
  return front && back ? RegionSide::Both : (back ? RegionSide::Back : RegionSide::Front);
}

}  // namespace

Partitioner::Partitioner(SolidTree& work, MergeStats& stats, MergeOptions options, Ref first_node)
    : w_(work), stats_(stats), eps_(work.tol.plane_eps), options_(options), first_node_(first_node) {}

void Partitioner::forget_boxes_from(Ref first_moved) {
  const auto kept = static_cast<std::size_t>(std::max<Ref>(first_moved - first_node_, 0));
  if (boxes_.size() > kept) {
    boxes_.resize(kept);
    box_known_.resize(kept);
  }
}

const Box& Partitioner::subtree_box(Ref t) {
  const auto slots = w_.nodes.size() - static_cast<std::size_t>(first_node_);
  if (boxes_.size() < slots) {
    boxes_.resize(slots);
    box_known_.resize(slots, false);
  }
  const auto known = [&](Ref r) { return box_known_[static_cast<std::size_t>(r - first_node_)]; };
  stack_.assign(1, t);
  while (!stack_.empty()) {
    const Ref r = stack_.back();
    if (known(r)) {  // a subtree two parents share
      stack_.pop_back();
      continue;
    }
    const SolidNode n = w_.nodes[r];
    const bool front_ready = is_leaf(n.front) || known(n.front);
    const bool back_ready = is_leaf(n.back) || known(n.back);
    if (!front_ready) stack_.push_back(n.front);
    if (!back_ready) stack_.push_back(n.back);
    if (!front_ready || !back_ready) continue;
    Box b;
    for (const Vec3& p : w_.loops[w_.shp[r]]) b.add(p);
    for (const Ref c : {n.front, n.back})
      if (!is_leaf(c)) b.add(boxes_[static_cast<std::size_t>(c - first_node_)]);
    boxes_[static_cast<std::size_t>(r - first_node_)] = b;
    box_known_[static_cast<std::size_t>(r - first_node_)] = true;
    stack_.pop_back();
  }
  return boxes_[static_cast<std::size_t>(t - first_node_)];
}

int Partitioner::bounds_side(Ref t, const Plane& h) {
  if (!options_.prune_by_bounds || t < first_node_) return 0;
  const Box& b = subtree_box(t);
  if (b.empty()) return 0;  // no sub-hyperplane left: reduce() decides where such nodes go
  const Vec3 centre = b.center(), half = (b.hi - b.lo) * 0.5;
  const double v = h.distance(centre);
  const double r = std::abs(h.n.x) * half.x + std::abs(h.n.y) * half.y + std::abs(h.n.z) * half.z;
  if (v - r > eps_) return 1;
  if (v + r < -eps_) return -1;
  return 0;
}

// As the exact kernel's, but the tolerance may call shp(t1) coplanar with, or spanning, a node's
// plane within plane_eps of it: then the subtree is partitioned as usual.
Ref Partitioner::leaf_beyond(Ref t, std::uint32_t shp_h, const Plane& h, bool& ok) {
  std::uint64_t walked = 0;  // below t, which partition_descend() counted
  for (; !is_leaf(t); ++walked) {
    const SolidNode& n = w_.nodes[t];
    const Side s = classify_loop(w_.loops[shp_h], h, n.plane, eps_);
    if (s != Side::Front && s != Side::Back) {
      ok = false;
      return kOut;
    }
    t = n.child(s == Side::Front);
  }
  ok = true;
  stats_.partition_nodes += walked > 0 ? walked - 1 : 0;
  return t;
}

Ref Partitioner::node(const Plane& plane, std::uint32_t shp, Ref front, Ref back) {
  if (collapses(front, back)) return front;
  return w_.add_node(plane, shp, front, back);
}

Partitioner::Parts Partitioner::partition(Ref t, std::uint32_t shp_h, const Plane& h) {
  ++stats_.partition_calls;
  frames_.assign(1, {t, shp_h, Kind::Pending, true});
  parts_.clear();
  while (!frames_.empty()) {
    const std::size_t top = frames_.size() - 1;
    if (frames_[top].kind == Kind::Pending) {
      partition_descend(top, h);
      continue;
    }
    const PartFrame f = frames_[top];
    frames_.pop_back();
    parts_.push_back(partition_combine(f, h));
  }
  return parts_.back();
}

// Step 1 of partitionTree: where shp(t1) lies against h(T). A leaf, or coplanar planes, give the
// parts at once; otherwise the subtrees shp(t1) reaches are partitioned first (step 2).
void Partitioner::partition_descend(std::size_t top, const Plane& h) {
  const PartFrame f = frames_[top];
  if (is_leaf(f.t)) {
    frames_.pop_back();
    parts_.push_back({f.t, f.t});
    return;
  }
  ++stats_.partition_nodes;
  const SolidNode node = w_.nodes[f.t];
  bool prune = f.prune;
  if (const int side = prune ? bounds_side(f.t, h) : 0; side != 0) {  // T wholly on one side: no copy of its path
    bool ok = false;
    const Ref leaf = leaf_beyond(f.t, f.shp_h, h, ok);
    if (ok) {
      ++stats_.pruned;
      frames_.pop_back();
      parts_.push_back(side > 0 ? Parts{f.t, leaf} : Parts{leaf, f.t});
      return;
    }
    prune = false;
  }
  switch (classify_loop(w_.loops[f.shp_h], h, node.plane, eps_)) {
    case Side::Coplanar:
      // h(t1) = h(T) inside r(T): T's two sides are h(t1)'s two sides.
      frames_.pop_back();
      parts_.push_back(dot(node.plane.n, h.n) > 0 ? Parts{node.front, node.back} : Parts{node.back, node.front});
      return;
    case Side::Front:
      frames_[top].kind = Kind::InFront;
      frames_.push_back({node.front, f.shp_h, Kind::Pending, prune});
      return;
    case Side::Back:
      frames_[top].kind = Kind::InBack;
      frames_.push_back({node.back, f.shp_h, Kind::Pending, prune});
      return;
    case Side::Spanning: {
      split_loop(w_.loops[f.shp_h], node.plane, 0.0, front_, back_);
      ++stats_.shp_splits;
      const std::uint32_t in_front = w_.loops.add(front_);
      const std::uint32_t in_back = w_.loops.add(back_);
      frames_[top].kind = Kind::InBoth;
      frames_.push_back({node.back, in_back, Kind::Pending, prune});
      frames_.push_back({node.front, in_front, Kind::Pending, prune});
      return;
    }
  }
}

// Where shp(T) lies against h(t1), for the one-subtree cases: a spanning or coplanar answer there
// contradicts shp(t1) lying on one side of h(T), and the farther side decides.
bool Partitioner::shp_in_front(Ref t, const Plane& h) {
  const std::span<const Vec3> loop = w_.loops[w_.shp[t]];
  const Side s = classify_loop(loop, w_.nodes[t].plane, h, eps_);
  if (s == Side::Front) return true;
  if (s == Side::Back) return false;
  ++stats_.inconsistent;
  return mostly_in_front(loop, h);
}

// Step 3: T+ and T- from the parts of the subtrees that shp(t1) reached.
Partitioner::Parts Partitioner::partition_combine(const PartFrame& f, const Plane& h) {
  const SolidNode node = w_.nodes[f.t];
  std::uint32_t shp_t = w_.shp[f.t];
  if (f.kind == Kind::InBoth) {
    const Parts back = parts_.back();
    parts_.pop_back();
    const Parts front = parts_.back();
    parts_.pop_back();
    if (classify_loop(w_.loops[shp_t], node.plane, h, eps_) != Side::Spanning) ++stats_.inconsistent;
    // A part that collapses to a leaf needs no sub-hyperplane.
    const bool plus = !collapses(front.plus, back.plus), minus = !collapses(front.minus, back.minus);
    if (!plus && !minus) return {front.plus, front.minus};
    split_loop(w_.loops[shp_t], h, 0.0, front_, back_);
    ++stats_.shp_splits;
    return {plus ? this->node(node.plane, w_.loops.add(front_), front.plus, back.plus) : front.plus,
            minus ? this->node(node.plane, w_.loops.add(back_), front.minus, back.minus) : front.minus};
  }
  // shp(t1) lies in one subtree X of T; the other, Y, lies wholly on the side of h(t1) that shp(T)
  // is on (Figure 7), and T keeps its node on that side only.
  const Parts x = parts_.back();
  parts_.pop_back();
  const bool x_is_front = f.kind == Kind::InFront;
  const Ref y = x_is_front ? node.back : node.front;
  const auto with_y = [&](Ref x_part) {
    return x_is_front ? this->node(node.plane, shp_t, x_part, y) : this->node(node.plane, shp_t, y, x_part);
  };
  const bool y_in_front = shp_in_front(f.t, h);
  // shp(T) may reach past h(t1) by up to plane_eps; what reaches past is cut off, exactly.
  split_loop(w_.loops[shp_t], h, 0.0, front_, back_);
  const std::vector<Vec3>& trimmed = y_in_front ? front_ : back_;
  if (!trimmed.empty() && trimmed.size() != w_.loops[shp_t].size()) shp_t = w_.loops.add(trimmed);
  if (y_in_front) return {with_y(x.plus), x.minus};
  return {x.plus, with_y(x.minus)};
}


SolidTree reduce(const SolidTree& solid) {
  // 1. Nodes whose plane misses their region give way to the child on the region's side.
  SolidTree crossing = emit_preorder(solid, solid.root, [&](Ref r, const std::vector<Plane>& path) {
    while (!is_leaf(r) && solid.loops[solid.shp[r]].empty()) {
      const RegionSide side = region_side(solid, r, path);
      if (side == RegionSide::Both) break;
      r = solid.nodes[r].child(side == RegionSide::Front);
    }
    return r;
  });
  // 2. Children follow parents in pre-order, so one backward pass collapses every uniform subtree.
  std::vector<Ref> collapsed(crossing.nodes.size());
  for (std::size_t i = crossing.nodes.size(); i-- > 0;) {
    SolidNode& n = crossing.nodes[i];
    if (!is_leaf(n.front)) n.front = collapsed[n.front];
    if (!is_leaf(n.back)) n.back = collapsed[n.back];
    collapsed[i] = is_leaf(n.front) && n.front == n.back ? n.front : static_cast<Ref>(i);
  }
  const Ref root = is_leaf(crossing.root) ? crossing.root : collapsed[crossing.root];
  return emit_preorder(crossing, root, [](Ref r, const std::vector<Plane>&) { return r; });
}

SolidTree merge_with_table(const SolidTree& a, const SolidTree& b, const CellTable& table, MergeStats* stats,
                           MergeOptions options) {
  if (!(a.box.lo == b.box.lo && a.box.hi == b.box.hi))
    throw std::invalid_argument("merge: the operands were built in different boxes (see solid_box)");
  MergeStats local;
  MergeStats& st = stats ? *stats : local;
  st = {};
  const auto start = Clock::now();
  Ref b_root = kOut;
  SolidTree work = combined(a, b, b_root);
  work.box = a.box;
  work.tol = a.tol;
  work.root = Merger(work, table, st, options, static_cast<Ref>(a.nodes.size())).merge(a.root, b_root);
  st.merge_seconds = seconds_since(start);
  st.before = solid_size(work);
  const auto reduce_start = Clock::now();
  SolidTree result = reduce(work);
  st.reduce_seconds = seconds_since(reduce_start);
  st.after = solid_size(result);
  return result;
}

SolidTree merge(const SolidTree& a, const SolidTree& b, SetOp op, MergeStats* stats, MergeOptions options) {
  return merge_with_table(a, b, cell_table(op), stats, options);
}

}  // namespace bsp
