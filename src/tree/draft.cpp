#include "tree/draft.h"

#include <utility>

#include "common/page_allocator.h"

namespace bsp {

namespace {

// The pool renumbered in first-use order: nodes first, then fragments.
void renumber_planes(TreeDraft& d) {
  PlanePool renumbered;
  std::vector<std::uint32_t> pair(d.planes.size() / 2, kNull);  // old pair -> new pair's even index
  const auto remap = [&](std::uint32_t& p) {
    std::uint32_t& to = pair[p >> 1];
    if (to == kNull) to = renumbered.append_distinct(d.planes[p & ~1u]);
    p = to | (p & 1u);
  };
  for (DraftNode& n : d.nodes)
    if (n.plane != kNull) remap(n.plane);
  for (std::uint32_t& p : d.fragment_plane) remap(p);
  d.planes = std::move(renumbered);
}

// Fragment i of the draft, read where it is (TreeDraft::fragment_store).
FragmentView fragment_view(const TreeDraft& d, std::size_t i) {
  const std::uint32_t s = d.fragment_store.empty() ? 0 : d.fragment_store[i];
  return (s == 0 ? d.store : d.task_stores[s - 1]).view(d.fragments[i]);
}

bool any_tex_coords(const TreeDraft& d) {
  if (!d.store.has_tex_coords()) return false;  // every task's store was made like the main one
  for (std::size_t i = 0; i < d.fragments.size(); ++i)
    for (const TexCoord& t : fragment_view(d, i).uv)
      if (t.u != 0 || t.v != 0) return true;
  return false;
}

// Copies the fragments into the flat array in node order, in parallel: a million fragments take a
// few hundred milliseconds to copy on one thread.
void pack(const TreeDraft& d, FragmentArray& out) {
  std::vector<std::uint32_t> counts(d.fragments.size()), sources(d.fragments.size());
  for (std::size_t i = 0; i < d.fragments.size(); ++i) {
    const FragmentView f = fragment_view(d, i);
    counts[i] = static_cast<std::uint32_t>(f.size());
    sources[i] = f.source;
  }
  out.lay_out(counts, sources, any_tex_coords(d));
  const auto n = static_cast<std::int64_t>(d.fragments.size());
#pragma omp parallel for schedule(static) default(none) shared(d, out, n)
  for (std::int64_t i = 0; i < n; ++i) out.write(static_cast<std::size_t>(i), fragment_view(d, static_cast<std::size_t>(i)));
}

}  // namespace

// Everything but the fragments is converted first, and what only the build needed is dropped from
// the stores before the fragments are packed, so the peak (stores and packed copy both whole)
// holds as little else as it can.
Tree freeze(TreeDraft&& draft) {
  renumber_planes(draft);
  Tree tree;
  tree.shape = draft.shape;
  tree.tol = draft.tol;
  tree.bounds = draft.bounds;
  tree.stats = draft.stats;
  tree.planes = std::move(draft.planes);
  tree.fragment_plane = std::move(draft.fragment_plane);
  tree.nodes.reserve(draft.nodes.size());
  for (const DraftNode& n : draft.nodes) tree.nodes.push_back({n.plane, n.front, n.back, n.first});
  free_memory(draft.nodes);
  draft.store.drop_build_data();
  for (FragmentStore& s : draft.task_stores) s.drop_build_data();
  pack(draft, tree.fragments);
  draft.store = FragmentStore{};
  draft.task_stores.clear();
  free_memory(draft.fragments);
  free_memory(draft.fragment_store);
  return tree;
}

}  // namespace bsp
