#include "tree/build_input.h"

namespace bsp {

namespace {

bool is_planar(const Polygon& poly, const Plane& plane, double eps) {
  for (const auto& v : poly.verts)
    if (std::abs(plane.distance(v.p)) > eps) return false;
  return true;
}

// Adds one convex planar polygon, or drops it as a sliver; vertices within eps of each other merge
// first, and the area that shaves off counts as dropped.
void add_one(Polygon&& poly, Tree& tree, FragmentStore& store, std::vector<std::uint32_t>& ids) {
  const double eps = tree.tol.plane_eps;
  tree.stats.dropped_area += merge_close_vertices(poly, eps);
  const auto plane = supporting_plane(poly);
  if (!plane || is_sliver(poly, eps)) {
    ++tree.stats.dropped_input;
    tree.stats.dropped_area += poly.verts.size() >= 3 ? area(poly) : 0.0;
    return;
  }
  ids.push_back(store.add(std::move(poly), tree.planes.add(*plane)));
}

}  // namespace

std::vector<std::uint32_t> load_input(std::span<const Polygon> input, Tree& tree, FragmentStore& store) {
  for (const auto& poly : input)
    for (const auto& v : poly.verts) tree.bounds.add(v.p);
  tree.tol = Tolerance::for_extent(tree.bounds.diagonal());
  tree.stats.n_input = input.size();
  std::vector<std::uint32_t> ids;
  ids.reserve(input.size());
  for (std::uint32_t source = 0; source < input.size(); ++source) {
    const Polygon& poly = input[source];
    tree.stats.input_area += poly.verts.size() >= 3 ? area(poly) : 0.0;
    const auto plane = supporting_plane(poly);
    if (!plane || poly.verts.size() == 3 || is_planar(poly, *plane, tree.tol.plane_eps)) {
      add_one(Polygon{poly.verts, source}, tree, store, ids);
      continue;
    }
    // Not planar within the tolerance: a fan of triangles keeps the area and the attributes.
    tree.stats.triangulated_extra += poly.verts.size() - 3;
    for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i)
      add_one(Polygon{{poly.verts[0], poly.verts[i], poly.verts[i + 1]}, source}, tree, store, ids);
  }
  return ids;
}

}  // namespace bsp
