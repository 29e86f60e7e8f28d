#include "solid/exact_merge.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>
#include <stdexcept>
#include <vector>

#include "solid/compaction.h"

namespace bsp {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr std::uint32_t kNone = FragmentStore::kNone;

[[noreturn]] void broken(const char* what) {
  throw std::logic_error(std::string("exact merge: ") + what + " (a broken invariant of exact solid trees)");
}

// Both operands in one node array: A's nodes keep their indices, B's follow; sub-hyperplanes are
// shared by id.
ExactSolidTree combined(const ExactSolidTree& a, const ExactSolidTree& b, Ref& b_root) {
  ExactSolidTree w = a;
  const Ref offset = static_cast<Ref>(a.nodes.size());
  for (std::size_t i = 0; i < b.nodes.size(); ++i) {
    ExactSolidNode n = b.nodes[i];
    if (!is_leaf(n.front)) n.front += offset;
    if (!is_leaf(n.back)) n.back += offset;
    w.add_node(n.plane, b.shp[i], n.front, n.back);
  }
  b_root = is_leaf(b.root) ? b.root : b.root + offset;
  return w;
}

// The sub-hyperplanes a merge makes, each held by one node of the work array at a time: a node
// partitionTree passes on whole (Figure 7's T on one side) hands its sub-hyperplane to its
// replacement, a complement's copy takes the original's, and a node whose sub-hyperplane is split
// leaves the parts to two new nodes. A made sub-hyperplane is released as soon as its node is
// garbage (split, or in a subtree a cell operation drops), so the store holds about what the
// merge's live trees hold rather than everything the merge ever made; the operands' are never
// released. Nodes below `first_made_node` are the operands' (combined()), which point only to
// operands' nodes. A subtree pruning by bounds passes on whole keeps its nodes, and their
// sub-hyperplanes, where they are.
class MadeShps {
 public:
  MadeShps(const ExactSolidTree& a, const ExactSolidTree& b, ExactFragments& store, Ref first_made_node)
      : store_(store), first_made_node_(first_made_node) {
    for (const auto* t : {&a, &b})
      for (const std::uint32_t id : t->shp) mark(operand_, id);
  }
  bool made_node(Ref r) const { return !is_leaf(r) && r >= first_made_node_; }
  bool operands(std::uint32_t id) const { return id < operand_.size() && operand_[id]; }
  void add(std::uint32_t id) { mark(live_, id); }
  // The sub-hyperplane leaves the merge's keeping (its node is garbage); the caller releases it.
  void forget(std::uint32_t id) {
    if (id >= live_.size() || !live_[id]) broken("a made sub-hyperplane dropped twice");
    live_[id] = false;
  }
  void release(std::uint32_t id) {
    forget(id);
    store_.release(id);
  }
  // Releases the made sub-hyperplanes of a dropped subtree (a cell operation's Out or In).
  void drop(const ExactSolidTree& w, Ref t) {
    if (!made_node(t)) return;
    stack_.assign(1, t);
    while (!stack_.empty()) {
      const Ref r = stack_.back();
      stack_.pop_back();
      if (!operands(w.shp[r])) release(w.shp[r]);  // a node the merge made may hold an operand's
      for (const Ref c : {w.nodes[r].front, w.nodes[r].back})
        if (made_node(c)) stack_.push_back(c);
    }
  }
  // Releases the live made sub-hyperplanes the result does not hold.
  void release_unused(const ExactSolidTree& result) {
    std::vector<bool> used(live_.size(), false);
    for (const std::uint32_t id : result.shp)
      if (id < used.size()) used[id] = true;
    for (std::uint32_t id = 0; id < live_.size(); ++id)
      if (live_[id] && !used[id]) release(id);
  }

 private:
  static void mark(std::vector<bool>& bits, std::uint32_t id) {
    if (id >= bits.size()) bits.resize(std::max<std::size_t>(id + 1, bits.size() * 2), false);
    bits[id] = true;
  }
  ExactFragments& store_;
  Ref first_made_node_;
  std::vector<bool> operand_, live_;
  std::vector<Ref> stack_;
};

// partitionTree (§4.1) as merge.h's Partitioner, exact. The pieces of shp(t1) made while
// descending are only looked at, and released as soon as they are; the parts of shp(T) become
// nodes' sub-hyperplanes (MadeShps).
class ExactPartitioner {
 public:
  // Nodes below `first_node` (A's) are never partitioned: the side array of boxes starts there.
  ExactPartitioner(ExactSolidTree& work, ExactSolidSpace& space, MergeStats& stats, MadeShps& made,
                   MergeOptions options, Ref first_node)
      : w_(work), store_(space.shps()), stats_(stats), made_(made), options_(options), first_node_(first_node) {}

  struct Parts {
    Ref plus, minus;
  };
  // Nodes from `first_moved` on were renumbered (compaction.h): their boxes are recomputed on demand.
  void forget_boxes_from(Ref first_moved) {
    const auto kept = static_cast<std::size_t>(std::max<Ref>(first_moved - first_node_, 0));
    if (boxes_.size() > kept) {
      boxes_.resize(kept);
      box_known_.resize(kept);
    }
  }
  Parts partition(Ref t, std::uint32_t shp_h, std::uint32_t h) {
    ++stats_.partition_calls;
    frames_.assign(1, {t, shp_h, false, Kind::Pending});
    parts_.clear();
    while (!frames_.empty()) {
      const std::size_t top = frames_.size() - 1;
      if (frames_[top].kind == Kind::Pending) {
        descend(top, h);
        continue;
      }
      const Frame f = frames_[top];
      frames_.pop_back();
      parts_.push_back(combine(f, h));
    }
    return parts_.back();
  }

 private:
  enum class Kind : std::uint8_t { Pending, InFront, InBack, InBoth };
  struct Frame {
    Ref t;
    std::uint32_t shp_h;  // shp(t1) inside r(T)
    bool owned;           // a piece made here, released when done with
    Kind kind;
  };

  void done_with(const Frame& f) {
    if (f.owned) store_.release(f.shp_h);
  }

  void descend(std::size_t top, std::uint32_t h) {
    Frame& f = frames_[top];
    if (is_leaf(f.t)) {
      done_with(f);
      parts_.push_back({f.t, f.t});
      frames_.pop_back();
      return;
    }
    ++stats_.partition_nodes;
    const ExactSolidNode node = w_.nodes[f.t];
    if (PlanePool::coplanar(node.plane, h)) {  // h(t1) = h(T): T's sides are h(t1)'s, T is garbage
      done_with(f);
      if (!made_.operands(w_.shp[f.t])) made_.release(w_.shp[f.t]);
      parts_.push_back(node.plane == h ? Parts{node.front, node.back} : Parts{node.back, node.front});
      frames_.pop_back();
      return;
    }
    if (const int side = bounds_side(f.t, h); side != 0) {  // T wholly on one side: no copy of its path
      ++stats_.pruned;
      const Ref leaf = leaf_beyond(f.t, f.shp_h);
      done_with(f);
      parts_.push_back(side > 0 ? Parts{f.t, leaf} : Parts{leaf, f.t});
      frames_.pop_back();
      return;
    }
    const Frame child{0, f.shp_h, f.owned, Kind::Pending};
    f.owned = false;  // handed down with the piece
    switch (store_.classify(f.shp_h, node.plane)) {
      case Side::Front:
        f.kind = Kind::InFront;
        frames_.push_back({node.front, child.shp_h, child.owned, Kind::Pending});
        return;
      case Side::Back:
        f.kind = Kind::InBack;
        frames_.push_back({node.back, child.shp_h, child.owned, Kind::Pending});
        return;
      case Side::Coplanar: broken("a piece of shp(t1) lies in another plane");
      case Side::Spanning: {
        const ExactFragments::Parts p = store_.split(f.shp_h, node.plane, !child.owned);
        ++stats_.shp_splits;
        f.kind = Kind::InBoth;
        frames_.push_back({node.back, p.back, true, Kind::Pending});
        frames_.push_back({node.front, p.front, true, Kind::Pending});
        return;
      }
    }
  }

  Ref node(std::uint32_t plane, std::uint32_t shp, Ref front, Ref back) { return w_.add_node(plane, shp, front, back); }

  int bounds_side(Ref t, std::uint32_t h) {
    if (!options_.prune_by_bounds || t < first_node_) return 0;
    return box_side(subtree_box(t), store_.planes().approx(h));
  }

  // The box of subtree t's sub-hyperplanes, each node's computed once, children first.
  FilterBox subtree_box(Ref t) {
    const auto slot = [&](Ref r) { return static_cast<std::size_t>(r - first_node_); };
    if (boxes_.size() < slot(static_cast<Ref>(w_.nodes.size()))) {
      boxes_.resize(slot(static_cast<Ref>(w_.nodes.size())));
      box_known_.resize(boxes_.size(), false);
    }
    stack_.assign(1, t);
    while (!stack_.empty()) {
      const Ref r = stack_.back();
      if (box_known_[slot(r)]) {  // a subtree two parents share
        stack_.pop_back();
        continue;
      }
      const ExactSolidNode n = w_.nodes[r];
      const bool front_ready = is_leaf(n.front) || box_known_[slot(n.front)];
      const bool back_ready = is_leaf(n.back) || box_known_[slot(n.back)];
      if (!front_ready) stack_.push_back(n.front);
      if (!back_ready) stack_.push_back(n.back);
      if (!front_ready || !back_ready) continue;
      FilterBox b = store_.box(w_.shp[r]);
      for (const Ref c : {n.front, n.back})
        if (!is_leaf(c)) b = united(b, boxes_[slot(c)]);
      boxes_[slot(r)] = b;
      box_known_[slot(r)] = true;
      stack_.pop_back();
    }
    return boxes_[slot(t)];
  }

  // The leaf of subtree t on the side of h(t1) where t has no sub-hyperplane: shp(t1) ∩ r(t) lies
  // there, in one child's region at each node. It cannot touch h(v) of a node v on the way: the
  // touching point would lie in shp(v) and on h(t1), which shp(v)'s box avoids.
  Ref leaf_beyond(Ref t, std::uint32_t shp_h) {
    for (bool counted = true; !is_leaf(t); counted = false) {
      if (!counted) ++stats_.partition_nodes;  // t itself was counted by descend()
      const ExactSolidNode n = w_.nodes[t];
      const Side s = store_.classify(shp_h, n.plane);
      if (s != Side::Front && s != Side::Back) broken("shp(t1) meets a node whose subtree lies on one side of h(t1)");
      t = s == Side::Front ? n.front : n.back;
    }
    return t;
  }

  // T's parts. A part whose two children are one leaf is that leaf (what reduce() would make of
  // it), and the part of shp(T) it would have held is never computed. T itself is garbage
  // afterwards: a sub-hyperplane the merge made goes with it unless a part takes it whole.
  Parts combine(const Frame& f, std::uint32_t h) {
    const ExactSolidNode n = w_.nodes[f.t];
    const std::uint32_t shp_t = w_.shp[f.t];
    const bool operands = made_.operands(shp_t);
    const Side s = store_.classify(shp_t, h);
    if (f.kind == Kind::InBoth) {
      const Parts back = parts_.back();
      parts_.pop_back();
      const Parts front = parts_.back();
      parts_.pop_back();
      if (s != Side::Spanning) broken("shp(t1) spans h(T) but shp(T) does not span h(t1)");
      const bool plus_leaf = same_leaf(front.plus, back.plus), minus_leaf = same_leaf(front.minus, back.minus);
      Parts out{front.plus, front.minus};
      if (!plus_leaf || !minus_leaf) ++stats_.shp_splits;
      if (!plus_leaf && !minus_leaf) {  // both parts: one pass over shp(T)'s vertices
        const ExactFragments::Parts p = store_.split(shp_t, h, true);
        made_.add(p.front);
        made_.add(p.back);
        out = {node(n.plane, p.front, front.plus, back.plus), node(n.plane, p.back, front.minus, back.minus)};
      } else if (!plus_leaf) {
        out.plus = node(n.plane, part_of(shp_t, h), front.plus, back.plus);
      } else if (!minus_leaf) {
        out.minus = node(n.plane, part_of(shp_t, PlanePool::flip(h)), front.minus, back.minus);
      }
      if (!operands) made_.release(shp_t);
      return out;
    }
    // shp(t1) lies in one subtree X of T; the other, Y, lies wholly on the side of h(t1) that shp(T)
    // is on (Figure 7), and T keeps its node, with shp(T) whole, on that side only.
    const Parts x = parts_.back();
    parts_.pop_back();
    if (s != Side::Front && s != Side::Back) broken("shp(t1) lies on one side of h(T) but shp(T) crosses h(t1)");
    const bool x_is_front = f.kind == Kind::InFront;
    const Ref y = x_is_front ? n.back : n.front;
    const auto with_y = [&](Ref x_part) {
      if (same_leaf(x_part, y)) {
        if (!operands) made_.release(shp_t);
        return y;
      }
      return x_is_front ? node(n.plane, shp_t, x_part, y) : node(n.plane, shp_t, y, x_part);
    };
    if (s == Side::Front) return {with_y(x.plus), x.minus};
    return {x.plus, with_y(x.minus)};
  }

  static bool same_leaf(Ref a, Ref b) { return is_leaf(a) && a == b; }

  // The part of shp(T) in front of pooled plane `h`, made alone; shp(T) stays.
  std::uint32_t part_of(std::uint32_t shp_t, std::uint32_t h) {
    const std::uint32_t part = store_.clip(shp_t, h, true);
    if (part == shp_t || part == kNone) broken("shp(T) does not span h(t1)");
    made_.add(part);
    return part;
  }

  ExactSolidTree& w_;
  ExactFragments& store_;
  MergeStats& stats_;
  MadeShps& made_;
  const MergeOptions options_;
  const Ref first_node_;
  std::vector<FilterBox> boxes_;  // node first_node_ + i at i (exact_merge.h), filled on demand
  std::vector<bool> box_known_;
  std::vector<Ref> stack_;
  std::vector<Frame> frames_;
  std::vector<Parts> parts_;
};

class ExactMerger {
 public:
  ExactMerger(ExactSolidTree& work, ExactSolidSpace& space, const CellTable& table, MergeStats& stats, MadeShps& made,
              MergeOptions options, Ref first_b)
      : w_(work), table_(table), stats_(stats), made_(made), partitioner_(work, space, stats, made, options, first_b),
        compactor_(options.compaction, static_cast<Ref>(work.nodes.size())) {}

  Ref merge(Ref a_root, Ref b_root) {
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
        const ExactSolidNode na = w_.nodes[f.a];
        const ExactPartitioner::Parts p = partitioner_.partition(f.b, w_.shp[f.a], na.plane);
        frames.back().combining = true;
        frames.push_back({na.back, p.minus, false});
        frames.push_back({na.front, p.plus, false});
        continue;
      }
      const Ref back = results.back();
      results.pop_back();
      const Ref front = results.back();
      results.pop_back();
      // Two children of one leaf are that leaf, as reduce() would make them.
      results.push_back(is_leaf(front) && front == back ? front : w_.add_node(w_.nodes[f.a].plane, w_.shp[f.a], front, back));
      frames.pop_back();
    }
    return results.back();
  }

 private:
  struct Frame {
    Ref a, b;
    bool combining;  // b is partitioned: waiting for the children's results
  };

  // A sub-hyperplane is an id in the space's store and moves with its node (MadeShps keeps the
  // store's account); the boxes of the nodes that moved are recomputed when asked for.
  void compact_if_due(std::vector<Frame>& frames, std::vector<Ref>& results) {
    const std::optional<std::uint64_t> reclaimed = compactor_.run_if_due(w_.nodes, w_.shp, frames, results);
    if (!reclaimed) return;
    partitioner_.forget_boxes_from(compactor_.first_made());
    ++stats_.compactions;
    stats_.compacted_nodes += *reclaimed;
  }

  Ref cell_op(Ref a, Ref b) {
    ++stats_.cell_ops;
    const bool a_is_cell = is_leaf(a);
    const CellResult r = a_is_cell ? table_.first_leaf[a == kIn] : table_.second_leaf[b == kIn];
    const Ref tree = a_is_cell ? b : a;
    switch (r) {
      case CellResult::Out: made_.drop(w_, tree); return kOut;
      case CellResult::In: made_.drop(w_, tree); return kIn;
      case CellResult::Tree: return tree;
      case CellResult::Complement: return complement(tree);
    }
    return kOut;
  }

  // A copy of the subtree with its leaves flipped; the copies share the original's sub-hyperplanes.
  Ref complement(Ref t) {
    if (is_leaf(t)) return flip_label(t);
    const auto copy = [&](Ref from) {
      ++stats_.complement_nodes;
      const ExactSolidNode n = w_.nodes[from];
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

  ExactSolidTree& w_;
  const CellTable& table_;
  MergeStats& stats_;
  MadeShps& made_;
  ExactPartitioner partitioner_;
  Compactor compactor_;
};

}  // namespace

ExactSolidTree reduce(const ExactSolidTree& solid) {
  // 1. Each reachable node's replacement: a leaf when both its children's are that leaf, resolved
  // children before parents, each node once (merging makes a tree, but a caller's array may share
  // a subtree between parents, and this walk stays linear then).
  constexpr Ref kUnresolved = 0x7fffffff;
  std::vector<Ref> to(solid.nodes.size(), kUnresolved);
  const auto resolved = [&](Ref r) { return is_leaf(r) ? r : to[r]; };
  std::vector<Ref> stack;
  if (!is_leaf(solid.root)) stack.push_back(solid.root);
  while (!stack.empty()) {
    const Ref r = stack.back();
    if (to[r] != kUnresolved) {
      stack.pop_back();
      continue;
    }
    const ExactSolidNode& n = solid.nodes[r];
    const Ref f = resolved(n.front), b = resolved(n.back);
    if (f == kUnresolved || b == kUnresolved) {
      if (f == kUnresolved) stack.push_back(n.front);
      if (b == kUnresolved) stack.push_back(n.back);
      continue;
    }
    to[r] = is_leaf(f) && f == b ? f : r;
    stack.pop_back();
  }
  // 2. The nodes that remain, in pre-order.
  ExactSolidTree out;
  struct Item {
    Ref from;
    Ref parent;  // in out; -1 for the root
    bool front;
  };
  std::vector<Item> items{{solid.root, -1, true}};
  while (!items.empty()) {
    const Item item = items.back();
    items.pop_back();
    Ref placed = resolved(item.from);
    if (!is_leaf(placed)) {
      const ExactSolidNode& n = solid.nodes[placed];
      placed = out.add_node(n.plane, solid.shp[item.from], kOut, kOut);
      items.push_back({n.back, placed, false});
      items.push_back({n.front, placed, true});
    }
    if (item.parent < 0)
      out.root = placed;
    else
      (item.front ? out.nodes[item.parent].front : out.nodes[item.parent].back) = placed;
  }
  return out;
}

ExactSolidTree merge_with_table(const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space,
                                const CellTable& table, MergeStats* stats, MergeOptions options) {
  MergeStats local;
  MergeStats& st = stats ? *stats : local;
  st = {};
  const auto start = Clock::now();
  Ref b_root = kOut;
  ExactSolidTree work = combined(a, b, b_root);
  MadeShps made(a, b, space.shps(), static_cast<Ref>(work.nodes.size()));
  work.root = ExactMerger(work, space, table, st, made, options, static_cast<Ref>(a.nodes.size())).merge(a.root, b_root);
  st.merge_seconds = seconds_since(start);
  st.before = solid_size(work);
  const auto reduce_start = Clock::now();
  ExactSolidTree result = reduce(work);
  made.release_unused(result);
  st.reduce_seconds = seconds_since(reduce_start);
  st.after = solid_size(result);
  return result;
}

void discard(const ExactSolidTree& result, const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space) {
  std::uint32_t ids = 0;
  for (const std::uint32_t id : result.shp) ids = std::max(ids, id + 1);
  std::vector<bool> keep(ids, false), released(ids, false);
  for (const auto* t : {&a, &b})
    for (const std::uint32_t id : t->shp)
      if (id < ids) keep[id] = true;
  for (const std::uint32_t id : result.shp)  // a subtree two parents share is stored twice, its shps once
    if (!keep[id] && !released[id]) {
      space.shps().release(id);
      released[id] = true;
    }
}

ExactSolidTree merge(const ExactSolidTree& a, const ExactSolidTree& b, ExactSolidSpace& space, SetOp op,
                     MergeStats* stats, MergeOptions options) {
  return merge_with_table(a, b, space, cell_table(op), stats, options);
}

}  // namespace bsp
