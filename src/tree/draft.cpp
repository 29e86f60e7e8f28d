#include "tree/draft.h"

#include <utility>

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

bool has_tex_coords(const std::vector<Polygon>& polys) {
  for (const Polygon& p : polys)
    for (const Vertex& v : p.verts)
      if (v.u != 0 || v.v != 0) return true;
  return false;
}

// Copies the polygons into the flat array, releasing each one as it goes, in parallel: a million
// fragments take a few hundred milliseconds to copy and free on one thread.
void pack(std::vector<Polygon>& polys, FragmentArray& out) {
  std::vector<std::uint32_t> counts(polys.size()), sources(polys.size());
  for (std::size_t i = 0; i < polys.size(); ++i) {
    counts[i] = static_cast<std::uint32_t>(polys[i].verts.size());
    sources[i] = polys[i].source;
  }
  out.lay_out(counts, sources, has_tex_coords(polys));
  const auto n = static_cast<std::int64_t>(polys.size());
#pragma omp parallel for schedule(static) default(none) shared(polys, out, n)
  for (std::int64_t i = 0; i < n; ++i) {
    out.write(static_cast<std::size_t>(i), polys[static_cast<std::size_t>(i)]);
    polys[static_cast<std::size_t>(i)] = Polygon{};
  }
  polys = {};
}

}  // namespace

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
  draft.nodes = {};
  pack(draft.fragments, tree.fragments);
  return tree;
}

}  // namespace bsp
