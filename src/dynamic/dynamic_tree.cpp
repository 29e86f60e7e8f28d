#include "dynamic/dynamic_tree.h"

#include <algorithm>
#include <utility>

#include "tree/build.h"
#include "tree/build_input.h"

namespace bsp {

Box bounds_of(std::span<const Polygon> a, std::span<const Polygon> b) {
  Box box;
  for (const auto set : {a, b})
    for (const Polygon& p : set)
      for (const Vertex& v : p.verts) box.add(v.p);
  return box;
}

DynamicTree::DynamicTree(std::span<const Polygon> static_polys, std::size_t objects, std::size_t moving_per_object,
                         const Box& bounds)
    : static_count_(static_polys.size()), per_object_(moving_per_object) {
  draft_.bounds = bounds;
  draft_.tol = Tolerance::for_extent(bounds.diagonal());
  draft_.log_splits = true;
  counters_.resize(objects + 1);
  holds_.resize(objects + 1);
  made_.resize(objects + 1);
  static_ids_ = add_input(static_polys, 0, draft_, counters_[kStaticOwner]);
  counters_[kStaticOwner].n_input = static_polys.size();
}

std::vector<std::uint32_t> DynamicTree::load_object(std::uint32_t k, std::span<const Polygon> polys) {
  BuildStats& c = counters_[k + 1];
  c.n_input += polys.size();
  return add_input(polys, static_cast<std::uint32_t>(static_count_ + k * per_object_), draft_, c);
}

std::uint32_t DynamicTree::owner_of_source(std::uint32_t source) const {
  if (source < static_count_) return kStaticOwner;
  return static_cast<std::uint32_t>(1 + (source - static_count_) / per_object_);
}

std::uint32_t DynamicTree::owner_of_fragment(std::uint32_t id) const { return owner_of_source(draft_.store.source(id)); }

std::uint32_t DynamicTree::add_fragment(const Polygon& poly, std::uint32_t plane) { return draft_.store.add(poly, plane); }

void DynamicTree::count_input(std::uint32_t owner, const BuildStats& built) {
  BuildStats& c = counters_[owner];
  c.n_input += built.n_input;
  c.splits += built.splits;
  c.dropped_input += built.dropped_input;
  c.dropped_slivers += built.dropped_slivers;
  c.triangulated_extra += built.triangulated_extra;
  c.input_area += built.input_area;
  c.dropped_area += built.dropped_area;
}

void DynamicTree::count_split(std::uint32_t owner, const FragmentStore::Parts& parts) {
  BuildStats& c = counters_[owner];
  ++c.splits;
  c.dropped_slivers += static_cast<std::uint64_t>(parts.dropped);
  c.dropped_area += parts.dropped_area;
}

std::uint32_t DynamicTree::new_node(std::uint32_t plane, std::uint32_t owner, std::uint32_t parent) {
  std::uint32_t n;
  if (!free_.empty()) {
    n = free_.back();
    free_.pop_back();
  } else {
    n = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
  }
  nodes_[n] = DynNode{plane, kNull, kNull, parent, owner, {}};
  made_[owner].push_back(n);
  return n;
}

void DynamicTree::free_node(std::uint32_t n) {
  nodes_[n] = DynNode{};
  nodes_[n].owner = kFreedNode;
  free_.push_back(n);
}

void DynamicTree::link(Slot slot, std::uint32_t child) {
  if (slot.parent == kNull) root_ = child;
  else (slot.front ? nodes_[slot.parent].front : nodes_[slot.parent].back) = child;
  if (child != kNull) nodes_[child].parent = slot.parent;
}

Slot DynamicTree::slot_of(std::uint32_t node) const {
  const std::uint32_t p = nodes_[node].parent;
  return p == kNull ? Slot{} : Slot{p, nodes_[p].front == node};
}

std::uint32_t DynamicTree::add_node(Slot slot, std::uint32_t plane, std::uint32_t owner) {
  const std::uint32_t n = new_node(plane, owner, slot.parent);
  link(slot, n);
  return n;
}

void DynamicTree::add_fragments(std::uint32_t node, std::span<const std::uint32_t> ids) {
  for (const std::uint32_t id : ids) {
    nodes_[node].frags.push_back(id);
    holds_[owner_of_fragment(id)].push_back(node);
  }
}

std::uint32_t DynamicTree::insert_above(std::uint32_t node, std::uint32_t plane, std::uint32_t owner, bool node_side) {
  const Slot slot = slot_of(node);
  const std::uint32_t s = add_node(slot, plane, owner);
  link(Slot{s, node_side}, node);
  return s;
}

std::vector<std::uint32_t> DynamicTree::cell_planes(Slot slot) const {
  std::vector<std::uint32_t> planes;
  for (Slot s = slot; s.parent != kNull; s = slot_of(s.parent)) {
    const std::uint32_t p = nodes_[s.parent].plane;
    planes.push_back(s.front ? p : PlanePool::flip(p));
  }
  std::reverse(planes.begin(), planes.end());
  return planes;
}

std::uint32_t DynamicTree::depth_of(std::uint32_t n) const {
  std::uint32_t d = 0;
  for (; n != kNull; n = nodes_[n].parent) ++d;
  return d;
}

std::uint64_t DynamicTree::path_key(Slot slot) const {
  std::vector<bool> sides;
  for (Slot s = slot; s.parent != kNull; s = slot_of(s.parent)) sides.push_back(s.front);
  std::uint64_t key = SplitContext::kRootKey;
  for (auto it = sides.rbegin(); it != sides.rend(); ++it) key = SplitContext::child_key(key, *it);
  return key;
}

// Nodes built from mixed owners' fragments (a frame-0 build, a repair) belong to the owner of the
// fragments on their plane; a node of a free plane with none belongs to `owner`.
void DynamicTree::build_at(Slot slot, std::vector<std::uint32_t> ids, std::uint32_t owner, Splitter& splitter,
                           UpdateWork& work) {
  work.polygons_built += ids.size();
  const std::uint32_t depth = slot.parent == kNull ? 1 : depth_of(slot.parent) + 1;
  build_subtree(draft_, splitter, std::move(ids), cell_planes(slot), depth, path_key(slot));
  std::vector<std::uint32_t> to(draft_.nodes.size());
  for (std::size_t i = 0; i < to.size(); ++i) {
    const DraftNode& d = draft_.nodes[i];
    const std::uint32_t o = d.count > 0 ? owner_of_fragment(draft_.fragments[d.first]) : owner;
    to[i] = new_node(d.plane, o, kNull);
  }
  for (std::size_t i = 0; i < to.size(); ++i) {
    const DraftNode& d = draft_.nodes[i];
    DynNode& n = nodes_[to[i]];
    n.front = d.front == kNull ? kNull : to[d.front];
    n.back = d.back == kNull ? kNull : to[d.back];
    for (const std::uint32_t c : {n.front, n.back})
      if (c != kNull) nodes_[c].parent = to[i];
    add_fragments(to[i], std::span(draft_.fragments).subspan(d.first, d.count));
  }
  link(slot, to[0]);
  for (const SplitRecord& r : draft_.split_log)
    count_split(owner_of_source(r.source), {FragmentStore::kNone, FragmentStore::kNone, static_cast<int>(r.dropped), r.dropped_area});
  counters_[kStaticOwner].fallbacks += draft_.stats.fallbacks;
  work.nodes_built += to.size();
  draft_.nodes.clear();
  draft_.fragments.clear();
  draft_.fragment_plane.clear();
  draft_.split_log.clear();
  draft_.stats = {};
}

void DynamicTree::build_all(std::vector<std::uint32_t> ids, Splitter& splitter, UpdateWork& work) {
  ids.insert(ids.begin(), static_ids_.begin(), static_ids_.end());
  if (root_ != kNull || ids.empty()) return;
  build_at(Slot{}, std::move(ids), kStaticOwner, splitter, work);
}

void DynamicTree::insert(std::vector<std::uint32_t> ids, std::uint32_t owner, Splitter& splitter, UpdateWork& work,
                         std::uint32_t start) {
  if (ids.empty()) return;
  work.fragments_inserted += ids.size();
  if (start == kNull) start = root_;
  if (start == kNull) {
    build_at(Slot{}, std::move(ids), owner, splitter, work);
    return;
  }
  std::vector<Pending> stack;
  stack.push_back({start, std::move(ids)});
  while (!stack.empty()) {
    Pending p = std::move(stack.back());
    stack.pop_back();
    filter(p.node, p.ids, owner, stack, splitter, work);
  }
}

void DynamicTree::filter(std::uint32_t n, std::vector<std::uint32_t>& ids, std::uint32_t owner,
                         std::vector<Pending>& stack, Splitter& splitter, UpdateWork& work) {
  const Plane plane = draft_.planes[nodes_[n].plane];
  const double eps = draft_.tol.plane_eps;
  std::vector<std::uint32_t> front, back, on;
  for (const std::uint32_t id : ids) {
    switch (draft_.store.classify(id, plane, eps)) {
      case Side::Coplanar: on.push_back(id); break;
      case Side::Front: front.push_back(id); break;
      case Side::Back: back.push_back(id); break;
      case Side::Spanning: {
        const std::uint32_t o = owner_of_fragment(id);
        const FragmentStore::Parts parts = draft_.store.split(id, plane, eps);
        count_split(o, parts);
        if (parts.front != FragmentStore::kNone) front.push_back(parts.front);
        if (parts.back != FragmentStore::kNone) back.push_back(parts.back);
        break;
      }
    }
  }
  add_fragments(n, on);
  for (const bool side : {false, true}) {
    std::vector<std::uint32_t>& part = side ? front : back;
    if (part.empty()) continue;
    const std::uint32_t c = nodes_[n].child(side);
    if (c != kNull) stack.push_back({c, std::move(part)});
    else build_at(Slot{n, side}, std::move(part), owner, splitter, work);
  }
}

std::vector<std::uint32_t> DynamicTree::owned_nodes(std::uint32_t owner) const {
  std::vector<std::uint32_t> out;
  for (const std::uint32_t n : made_[owner])
    if (nodes_[n].owner == owner) out.push_back(n);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void DynamicTree::remove_fragments(std::uint32_t owner, UpdateWork& work) {
  std::vector<std::uint32_t> held = std::move(holds_[owner]);
  holds_[owner].clear();
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  for (const std::uint32_t n : held) {
    if (nodes_[n].owner == kFreedNode) continue;
    std::vector<std::uint32_t>& frags = nodes_[n].frags;
    const auto keep = std::stable_partition(frags.begin(), frags.end(),
                                            [&](std::uint32_t id) { return owner_of_fragment(id) != owner; });
    for (auto it = keep; it != frags.end(); ++it) draft_.store.release(*it);
    work.fragments_removed += static_cast<std::uint64_t>(frags.end() - keep);
    frags.erase(keep, frags.end());
  }
}

// Nodes that keep another owner's fragments pass to that owner; the rest are dead.
void DynamicTree::collect_dead(std::uint32_t owner, std::vector<std::pair<std::uint32_t, std::uint32_t>>& dead) {
  for (const std::uint32_t n : owned_nodes(owner)) {
    if (nodes_[n].frags.empty()) {
      dead.push_back({depth_of(n), n});
    } else {
      nodes_[n].owner = owner_of_fragment(nodes_[n].frags.front());
      made_[nodes_[n].owner].push_back(n);
    }
  }
  made_[owner].clear();
}

// Dead nodes go deepest first, so a repair never meets a node that is about to go.
void DynamicTree::remove(std::span<const std::uint32_t> owners, Splitter& splitter, UpdateWork& work) {
  for (const std::uint32_t o : owners) remove_fragments(o, work);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> dead;  // (depth, node)
  for (const std::uint32_t o : owners) collect_dead(o, dead);
  std::sort(dead.begin(), dead.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  for (const auto& [depth, n] : dead) remove_dead(n, splitter, work);
  for (const std::uint32_t o : owners)
    if (o != kStaticOwner) counters_[o] = {};
}

void DynamicTree::remove_dead(std::uint32_t n, Splitter& splitter, UpdateWork& work) {
  const Slot slot = slot_of(n);
  const std::uint32_t f = nodes_[n].front, b = nodes_[n].back;
  ++work.nodes_removed;
  if (f == kNull || b == kNull) {
    link(slot, f == kNull ? b : f);
    free_node(n);
    return;
  }
  // Chrysanthou and Slater's open case [Chrysanthou §8]: both subtrees hold fragments. The larger
  // takes the node's place (its cell is the node's cell, minus nothing the other side needs: the
  // other side's fragments are reinserted into it, split by its planes).
  ++work.repairs;
  const bool keep_front = subtree_size(f) >= subtree_size(b);
  const std::uint32_t keep = keep_front ? f : b;
  std::vector<std::uint32_t> frags = dismantle(keep_front ? b : f, work);
  link(slot, keep);
  free_node(n);
  work.reinserted_fragments += frags.size();
  // One owner at a time: nodes built at empty cells belong to the owner whose fragments made them.
  std::stable_sort(frags.begin(), frags.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return owner_of_fragment(x) < owner_of_fragment(y); });
  for (std::size_t i = 0; i < frags.size();) {
    const std::uint32_t o = owner_of_fragment(frags[i]);
    std::size_t j = i;
    while (j < frags.size() && owner_of_fragment(frags[j]) == o) ++j;
    insert(std::vector<std::uint32_t>(frags.begin() + static_cast<std::ptrdiff_t>(i), frags.begin() + static_cast<std::ptrdiff_t>(j)),
           o, splitter, work, keep);
    i = j;
  }
}

std::uint64_t DynamicTree::subtree_size(std::uint32_t n) const {
  std::uint64_t size = 0;
  std::vector<std::uint32_t> stack{n};
  while (!stack.empty()) {
    const std::uint32_t x = stack.back();
    stack.pop_back();
    ++size;
    for (const std::uint32_t c : {nodes_[x].front, nodes_[x].back})
      if (c != kNull) stack.push_back(c);
  }
  return size;
}

std::vector<std::uint32_t> DynamicTree::dismantle(std::uint32_t n, UpdateWork& work) {
  std::vector<std::uint32_t> frags, stack{n};
  while (!stack.empty()) {
    const std::uint32_t x = stack.back();
    stack.pop_back();
    frags.insert(frags.end(), nodes_[x].frags.begin(), nodes_[x].frags.end());
    disturbed_.push_back(nodes_[x].owner);
    for (const std::uint32_t c : {nodes_[x].back, nodes_[x].front})
      if (c != kNull) stack.push_back(c);
    free_node(x);
    ++work.dismantled_nodes;
  }
  return frags;
}

std::vector<std::uint32_t> DynamicTree::take_disturbed() {
  std::vector<std::uint32_t> out = std::move(disturbed_);
  disturbed_.clear();
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Tree DynamicTree::snapshot() const {
  Tree tree;
  tree.shape = Shape::Strict;
  tree.tol = draft_.tol;
  tree.bounds = draft_.bounds;
  tree.planes = draft_.planes;
  std::vector<std::uint32_t> order, ids;  // nodes in pre-order, fragments in node order
  std::vector<std::uint32_t> stack;
  if (root_ != kNull) stack.push_back(root_);
  std::vector<std::uint32_t> index(nodes_.size(), kNull);
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    index[n] = static_cast<std::uint32_t>(order.size());
    order.push_back(n);
    if (nodes_[n].back != kNull) stack.push_back(nodes_[n].back);
    if (nodes_[n].front != kNull) stack.push_back(nodes_[n].front);
  }
  for (const std::uint32_t n : order) {
    const DynNode& d = nodes_[n];
    tree.nodes.push_back({d.plane, d.front == kNull ? kNull : index[d.front], d.back == kNull ? kNull : index[d.back],
                          static_cast<std::uint32_t>(ids.size())});
    ids.insert(ids.end(), d.frags.begin(), d.frags.end());
  }
  std::vector<std::uint32_t> counts, sources;
  for (const std::uint32_t id : ids) {
    counts.push_back(static_cast<std::uint32_t>(draft_.store.points(id).size()));
    sources.push_back(draft_.store.source(id));
    tree.fragment_plane.push_back(draft_.store.plane(id));
  }
  tree.fragments.lay_out(counts, sources, false);
  for (std::size_t i = 0; i < ids.size(); ++i) tree.fragments.write(i, draft_.store.view(ids[i]));
  for (const BuildStats& c : counters_) {
    tree.stats.n_input += c.n_input;
    tree.stats.splits += c.splits;
    tree.stats.dropped_input += c.dropped_input;
    tree.stats.dropped_slivers += c.dropped_slivers;
    tree.stats.triangulated_extra += c.triangulated_extra;
    tree.stats.input_area += c.input_area;
    tree.stats.dropped_area += c.dropped_area;
    tree.stats.fallbacks += c.fallbacks;
  }
  return tree;
}

}  // namespace bsp
