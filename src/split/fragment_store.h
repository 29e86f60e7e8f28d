#pragma once
// Scratch storage for the fragments of a build, in flat arrays: fragment `id`'s vertices are a span
// of one array of positions (and of one array of float texture coordinates when the input has
// any), with its source polygon, pooled supporting plane and bounding sphere in parallel arrays.
// The sphere lets most classifications decide with one plane evaluation instead of one per vertex.
//
// Memory: splitting a fragment releases it. Its id goes to the next fragment added, and its vertex
// span to the next fragment with as many vertices (up to kReusedSpan), so the arrays hold about the
// fragments alive, not every fragment the build ever made, and nothing is allocated per fragment.
// Ids and spans are reused in a fixed order: a build stays deterministic. The arrays give their
// memory back to the system when freed (PageAllocator): the main store's old arrays as soon as it
// is compacted, every store's as soon as freeze() has packed its fragments.
#include <cstdint>
#include <span>
#include <vector>

#include "common/page_allocator.h"
#include "common/prefetch.h"
#include "common/vector_path.h"
#include "geometry/fragment_array.h"
#include "geometry/plane.h"
#include "geometry/polygon.h"

namespace bsp {

struct BoundingSphere {
  Vec3 center;
  double radius = 0;
};

// Centred at the vertex average, reaching the farthest vertex.
BoundingSphere bounding_sphere(const Polygon& poly);

struct SideCounts {
  std::uint32_t front = 0, back = 0, coplanar = 0, spanning = 0;
};

class FragmentStore {
 public:
  static constexpr std::uint32_t kNone = 0xffffffffu;  // no fragment (a part split() dropped)
  // Freed spans of more vertices than this are not reused: fragments that large are rare (a store
  // whose polygons grow larger says so with reuse_spans_up_to).
  static constexpr std::uint32_t kReusedSpan = 16;
  // A store made for a known set of fragments reserves room for this many times as many (splits
  // add fragments): reserved pages cost nothing until written, and a store that has to grow
  // copies everything it holds.
  static constexpr std::size_t kGrowthRoom = 2;
  // Planes count_sides tests in one pass: their components and counts stay in L1 beside the loop.
  static constexpr std::size_t kPlaneBlock = 32;
  static_assert(kPlaneBlock <= 32 && kPlaneBlock % 4 == 0, "a bit per plane in a 32-bit mask, planes in fours");
  // Fragments count_sides tests against a block's spheres (or the exact kernel's boxes) before their
  // vertices: the vertices of those some plane straddles are prefetched meanwhile.
  static constexpr std::size_t kCountChunk = 32;

  // Texture coordinates are kept only when `tex_coords` (some input vertex has non-zero ones).
  FragmentStore() = default;
  explicit FragmentStore(bool tex_coords) : tex_(tex_coords) {}
  // Reuse freed spans of up to `count` vertices instead of kReusedSpan.
  void reuse_spans_up_to(std::uint32_t count) { reused_span_ = count; }
  bool has_tex_coords() const { return tex_; }

  std::uint32_t add(const Polygon& poly, std::uint32_t plane, const BoundingSphere& sphere);
  std::uint32_t add(const Polygon& poly, std::uint32_t plane) { return add(poly, plane, bounding_sphere(poly)); }
  // A fragment of another store (never of this one: growing the arrays would move what it views).
  std::uint32_t add(const FragmentView& f, std::uint32_t plane, const BoundingSphere& sphere);
  // Frees the fragment's id and vertices for reuse; `id` must not be used again until add returns it.
  void release(std::uint32_t id);
  void reserve(std::size_t fragments, std::size_t vertices);
  // Moves the live fragments to fresh arrays without the space released ones left, keeping their
  // order; returns each old id's new id (kNone for a released one).
  std::vector<std::uint32_t> compact();
  // Frees what only building needs (planes, spheres, free lists): afterwards only view() and
  // points() may be called.
  void drop_build_data();

  FragmentView view(std::uint32_t id) const;
  std::span<const Vec3> points(std::uint32_t id) const { return {pos_.data() + span_[id].first, span_[id].count}; }
  std::uint32_t plane(std::uint32_t id) const { return plane_[id]; }
  // Start loading plane(id) or sphere(id) into the cache, for a reader that knows which ids come next.
  void prefetch_plane(std::uint32_t id) const { __builtin_prefetch(plane_.data() + id); }
  void prefetch_sphere(std::uint32_t id) const { __builtin_prefetch(sphere_.data() + id); }
  std::uint32_t source(std::uint32_t id) const { return source_[id]; }
  const BoundingSphere& sphere(std::uint32_t id) const { return sphere_[id]; }
  std::size_t vertices_live() const { return live_vertices_; }
  std::size_t vertex_slots() const { return pos_.size(); }  // stored vertices, freed spans included

  // classify() with a bounding-sphere early-out; identical results. Inline: it is the build's
  // innermost operation, and the early-out decides most calls with one plane evaluation.
  Side classify(std::uint32_t id, const Plane& p, double eps) const {
    const BoundingSphere& s = sphere_[id];
    const double d = p.distance(s.center);
    ++side_tests_;
    if (d - s.radius > eps) return Side::Front;
    if (d + s.radius < -eps) return Side::Back;
    side_tests_ += span_[id].count;
    return bsp::classify(points(id), p, eps);
  }
  // The point-against-plane tests classify() has made since the store was made (BuildStats).
  std::uint64_t side_tests() const { return side_tests_; }
  SideCounts count_sides(std::span<const std::uint32_t> ids, const Plane& p, double eps) const;
  // count_sides for several planes in one pass over the fragments, added to out[j] for planes[j]
  // (out has planes.size() entries, zeroed for a fresh count): each fragment's sphere is read once
  // and tested against a block of planes held as arrays of their components, four planes per AVX
  // instruction where the processor has AVX (asked at run time), else two per SSE2 instruction
  // (the x86-64 baseline; scalar elsewhere), with no branch on the data; only a plane the sphere
  // straddles takes the per-vertex path, a chunk of fragments later. The same operations in the
  // same order as classify(), each rounded alike in a vector lane, so the same counts on every
  // path (common/vector_path.h).
  void count_sides(std::span<const std::uint32_t> ids, std::span<const Plane> planes, double eps,
                   std::span<SideCounts> out) const;
  // The vector instructions count_sides runs on (Widest unless a test asks for the other path).
  void use_vector_path(VectorPath path) { vector_path_ = path; }

  // Splits fragment `id` (classified Spanning) by the plane as bsp::split does and releases it; the
  // parts keep its supporting plane and source.
  struct Parts {
    std::uint32_t front = kNone, back = kNone;
    int dropped = 0;            // as SplitResult
    double dropped_area = 0.0;  // as SplitResult
  };
  Parts split(std::uint32_t id, const Plane& plane, double eps);

 private:
  struct Span {
    std::uint32_t first = 0, count = 0;
  };

  void count_block(std::span<const std::uint32_t> ids, std::span<const Plane> planes, double eps,
                   std::span<SideCounts> out) const;

  std::uint32_t new_id(Span span, std::uint32_t source, std::uint32_t plane, const BoundingSphere& sphere);
  Span new_span(std::uint32_t count);

  bool tex_ = false;
  VectorPath vector_path_ = VectorPath::Widest;
  std::uint32_t reused_span_ = kReusedSpan;
  PageVector<Vec3> pos_;
  PageVector<TexCoord> uv_;  // parallel to pos_ when tex_, else empty
  PageVector<Span> span_;    // per id
  PageVector<std::uint32_t> source_, plane_;
  PageVector<BoundingSphere> sphere_;
  PageVector<std::uint32_t> free_ids_;
  std::vector<std::vector<std::uint32_t>> free_spans_;  // by vertex count: first vertices of freed spans
  std::size_t live_vertices_ = 0;
  // A count, not state: classify() is logically const. A store is used by one thread at a time.
  mutable std::uint64_t side_tests_ = 0;
  Polygon whole_, front_, back_;  // split()'s scratch, whose memory every split reuses
};

// IS-CONVEX-SET [DividingPolygon]: every fragment lies in front of or on every other fragment's plane.
// O(k^2) plane tests in the worst case, with an early exit on the first failure.
bool is_convex_set(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                   const PlanePool& planes, double eps);

}  // namespace bsp
