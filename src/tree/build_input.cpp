#include "tree/build_input.h"

#include <algorithm>
#include <cmath>

#include "common/prefetch.h"
#include "geometry/segment2.h"

namespace bsp {

namespace {

// Input polygons are cleaned in parallel chunks of this many, then pooled in input order. The
// chunking is fixed, so sums over chunks (areas) round the same on every thread count.
constexpr std::size_t kLoadChunk = 4096;
// Chunks cleaned at once before they are pooled: enough to keep every thread busy, few enough that
// the cleaned copies (a heap polygon each) stay a small fraction of the store they go into, and the
// allocator reuses one window's memory for the next instead of holding a copy of the whole input.
constexpr std::size_t kLoadWindow = 32;

bool is_planar(const Polygon& poly, const Plane& plane, double eps) {
  for (const auto& v : poly.verts)
    if (std::abs(plane.distance(v.p)) > eps) return false;
  return true;
}

// A cleaned input fragment, ready to pool: its plane's hash is computed beside the cleaning, on
// every thread, so that pooling (in input order, on one) only looks it up.
struct Part {
  Polygon poly;
  Plane plane;
  BoundingSphere sphere;
  std::uint64_t plane_hash = 0;
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
  out.parts.push_back({std::move(poly), *plane, s, PlanePool::hash(*plane)});
}

// A 2D segment (geometry/segment2.h): pooled with its line; shorter than eps, dropped. Its length
// stands for area in the input and dropped totals.
void load_segment(const Polygon& seg, std::uint32_t source, double eps, Chunk& out) {
  const double len = std::hypot(seg.verts[1].p.x - seg.verts[0].p.x, seg.verts[1].p.y - seg.verts[0].p.y);
  out.input_area += len;
  const auto line = line_through(seg.verts[0].p, seg.verts[1].p);
  if (!line || len < eps) {
    ++out.dropped_input;
    out.dropped_area += len;
    return;
  }
  Polygon kept{seg.verts, source};
  const BoundingSphere s = bounding_sphere(kept);
  out.parts.push_back({std::move(kept), *line, s, PlanePool::hash(*line)});
}

void load_one(const Polygon& poly, std::uint32_t source, double eps, Chunk& out) {
  if (is_segment(poly)) {
    load_segment(poly, source, eps, out);
    return;
  }
  out.input_area += poly.verts.size() >= 3 ? area(poly) : 0.0;
  const auto plane = supporting_plane(poly);
  if (!plane || poly.verts.size() == 3 || is_planar(poly, *plane, eps)) {
    keep_one(Polygon{poly.verts, source}, eps, out);
    return;
  }
  // Not planar within the tolerance: a fan of triangles keeps the attributes and the area projected
  // onto the polygon's Newell normal (input_area), which is the sum of the triangles' projections.
  out.triangulated_extra += poly.verts.size() - 3;
  for (std::size_t i = 1; i + 1 < poly.verts.size(); ++i)
    keep_one(Polygon{{poly.verts[0], poly.verts[i], poly.verts[i + 1]}, source}, eps, out);
}

// Adds a cleaned chunk to the store and its counters to the stats, in input order, and empties it.
void pool_chunk(Chunk& c, TreeDraft& tree, BuildStats& stats, std::vector<std::uint32_t>& ids) {
  stats.input_area += c.input_area;
  stats.dropped_area += c.dropped_area;
  stats.dropped_input += c.dropped_input;
  stats.triangulated_extra += c.triangulated_extra;
  const std::size_t n = c.parts.size();
  for (std::size_t i = 0; i < n; ++i) {
    // The table slots and the cleaned polygons' vertices are scattered: a cache miss each.
    if (i + kPrefetchAhead < n) {
      const Part& ahead = c.parts[i + kPrefetchAhead];
      tree.planes.prefetch_slot(ahead.plane_hash);
      prefetch_bytes(ahead.poly.verts.data(), ahead.poly.verts.size() * sizeof(Vertex));
    }
    const Part& p = c.parts[i];
    ids.push_back(tree.store.add(p.poly, tree.planes.add(p.plane, p.plane_hash), p.sphere));
  }
  c = Chunk{};
}

}  // namespace

std::vector<std::uint32_t> load_input(std::span<const Polygon> input, TreeDraft& tree, double plane_eps_relative) {
  bool tex_coords = false;
  std::size_t vertices = 0;
  for (const auto& poly : input) {
    vertices += poly.verts.size();
    for (const auto& v : poly.verts) {
      tree.bounds.add(v.p);
      tex_coords |= v.u != 0 || v.v != 0;
    }
  }
  tree.tol = Tolerance::for_extent(tree.bounds.diagonal(), plane_eps_relative);
  tree.stats.n_input = input.size();
  tree.store = FragmentStore(tex_coords);
  tree.store.reserve(FragmentStore::kGrowthRoom * input.size(), FragmentStore::kGrowthRoom * vertices);
  tree.planes.reserve(input.size());
  return add_input(input, 0, tree, tree.stats);
}

std::vector<std::uint32_t> add_input(std::span<const Polygon> input, std::uint32_t first_source, TreeDraft& tree,
                                     BuildStats& stats) {
  const double eps = tree.tol.plane_eps;
  std::vector<std::uint32_t> ids;
  ids.reserve(input.size());
  const std::size_t chunk_count = (input.size() + kLoadChunk - 1) / kLoadChunk;
  std::vector<Chunk> window(kLoadWindow);
  for (std::size_t first = 0; first < chunk_count; first += kLoadWindow) {
    const std::size_t count = std::min(kLoadWindow, chunk_count - first);
#pragma omp parallel for schedule(dynamic, 1) default(none) shared(input, window, eps, first, count, first_source) if (count > 1)
    for (std::size_t c = 0; c < count; ++c) {
      const std::size_t begin = (first + c) * kLoadChunk, end = std::min(input.size(), begin + kLoadChunk);
      for (std::size_t i = begin; i < end; ++i)
        load_one(input[i], first_source + static_cast<std::uint32_t>(i), eps, window[c]);
    }
    for (std::size_t c = 0; c < count; ++c) pool_chunk(window[c], tree, stats, ids);
  }
  return ids;
}

}  // namespace bsp
