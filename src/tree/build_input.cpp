#include "tree/build_input.h"

#include <algorithm>

namespace bsp {

namespace {

// Input polygons are cleaned in parallel chunks of this many, then pooled in input order. The
// chunking is fixed, so sums over chunks (areas) round the same on every thread count.
constexpr std::size_t kLoadChunk = 4096;

bool is_planar(const Polygon& poly, const Plane& plane, double eps) {
  for (const auto& v : poly.verts)
    if (std::abs(plane.distance(v.p)) > eps) return false;
  return true;
}

// A cleaned input fragment, ready to pool.
struct Part {
  Polygon poly;
  Plane plane;
  BoundingSphere sphere;
};

// One chunk's parts in input order and its share of the input counters.
struct Chunk {
  std::vector<Part> parts;
  double input_area = 0, dropped_area = 0;
  std::uint64_t dropped_input = 0, triangulated_extra = 0;
};

// Keeps one convex planar polygon, or drops it as a sliver; vertices within eps of each other merge
// first, and the area that shaves off counts as dropped.
void keep_one(Polygon&& poly, double eps, Chunk& out) {
  out.dropped_area += merge_close_vertices(poly, eps);
  const auto plane = supporting_plane(poly);
  if (!plane || is_sliver(poly, eps)) {
    ++out.dropped_input;
    out.dropped_area += poly.verts.size() >= 3 ? area(poly) : 0.0;
    return;
  }
  const BoundingSphere s = bounding_sphere(poly);
  out.parts.push_back({std::move(poly), *plane, s});
}

void load_one(const Polygon& poly, std::uint32_t source, double eps, Chunk& out) {
  out.input_area += poly.verts.size() >= 3 ? area(poly) : 0.0;
  const auto plane = supporting_plane(poly);
  if (!plane || poly.verts.size() == 3 || is_planar(poly, *plane, eps)) {
    keep_one(Polygon{poly.verts, source}, eps, out);
    return;
  }
  // Not planar within the tolerance: a fan of triangles keeps the area and the attributes.
  out.triangulated_extra += poly.verts.size() - 3;
  for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i)
    keep_one(Polygon{{poly.verts[0], poly.verts[i], poly.verts[i + 1]}, source}, eps, out);
}

}  // namespace

std::vector<std::uint32_t> load_input(std::span<const Polygon> input, TreeDraft& tree, FragmentStore& store) {
  for (const auto& poly : input)
    for (const auto& v : poly.verts) tree.bounds.add(v.p);
  tree.tol = Tolerance::for_extent(tree.bounds.diagonal());
  tree.stats.n_input = input.size();
  const double eps = tree.tol.plane_eps;
  std::vector<Chunk> chunks((input.size() + kLoadChunk - 1) / kLoadChunk);
#pragma omp parallel for schedule(dynamic, 1) default(none) shared(input, chunks, eps)
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    const std::size_t end = std::min(input.size(), (c + 1) * kLoadChunk);
    for (std::size_t i = c * kLoadChunk; i < end; ++i) load_one(input[i], static_cast<std::uint32_t>(i), eps, chunks[c]);
  }
  std::vector<std::uint32_t> ids;
  ids.reserve(input.size());
  store.reserve(input.size());
  tree.planes.reserve(input.size());
  for (Chunk& c : chunks) {
    tree.stats.input_area += c.input_area;
    tree.stats.dropped_area += c.dropped_area;
    tree.stats.dropped_input += c.dropped_input;
    tree.stats.triangulated_extra += c.triangulated_extra;
    for (Part& p : c.parts) ids.push_back(store.add(std::move(p.poly), tree.planes.add(p.plane), p.sphere));
    c = Chunk{};
  }
  return ids;
}

}  // namespace bsp
