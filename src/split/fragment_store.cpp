#include "split/fragment_store.h"

#include <bit>
#include <cassert>
#include <limits>
#include <stdexcept>

#include "geometry/segment2.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace bsp {

BoundingSphere bounding_sphere(const Polygon& poly) {
  BoundingSphere s{centroid(poly), 0.0};
  for (const auto& v : poly.verts) s.radius = std::max(s.radius, length(v.p - s.center));
  return s;
}

FragmentStore::Span FragmentStore::new_span(std::uint32_t count) {
  live_vertices_ += count;
  if (count < free_spans_.size() && !free_spans_[count].empty()) {
    const std::uint32_t first = free_spans_[count].back();
    free_spans_[count].pop_back();
    return {first, count};
  }
  if (pos_.size() + count > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("a build's fragments have more than 2^32 vertices");
  const auto first = static_cast<std::uint32_t>(pos_.size());
  pos_.resize(pos_.size() + count);
  if (tex_) uv_.resize(pos_.size());
  return {first, count};
}

std::uint32_t FragmentStore::new_id(Span span, std::uint32_t source, std::uint32_t plane, const BoundingSphere& sphere) {
  if (!free_ids_.empty()) {
    const std::uint32_t id = free_ids_.back();
    free_ids_.pop_back();
    span_[id] = span;
    source_[id] = source;
    plane_[id] = plane;
    sphere_[id] = sphere;
    return id;
  }
  span_.push_back(span);
  source_.push_back(source);
  plane_.push_back(plane);
  sphere_.push_back(sphere);
  return static_cast<std::uint32_t>(span_.size() - 1);
}

std::uint32_t FragmentStore::add(const Polygon& poly, std::uint32_t plane, const BoundingSphere& sphere) {
  const Span s = new_span(static_cast<std::uint32_t>(poly.verts.size()));
  for (std::uint32_t k = 0; k < s.count; ++k) {
    const Vertex& v = poly.verts[k];
    pos_[s.first + k] = v.p;
    if (tex_) uv_[s.first + k] = {static_cast<float>(v.u), static_cast<float>(v.v)};
  }
  return new_id(s, poly.source, plane, sphere);
}

std::uint32_t FragmentStore::add(const FragmentView& f, std::uint32_t plane, const BoundingSphere& sphere) {
  assert(f.p.empty() || f.p.data() < pos_.data() || f.p.data() >= pos_.data() + pos_.size());
  const Span s = new_span(static_cast<std::uint32_t>(f.size()));
  std::copy(f.p.begin(), f.p.end(), pos_.begin() + s.first);
  if (tex_) {
    if (f.uv.empty()) std::fill_n(uv_.begin() + s.first, s.count, TexCoord{});
    else std::copy(f.uv.begin(), f.uv.end(), uv_.begin() + s.first);
  }
  return new_id(s, f.source, plane, sphere);
}

void FragmentStore::release(std::uint32_t id) {
  const Span s = span_[id];
  live_vertices_ -= s.count;
  if (s.count <= reused_span_) {
    if (free_spans_.size() <= s.count) free_spans_.resize(s.count + 1);
    free_spans_[s.count].push_back(s.first);
  }
  free_ids_.push_back(id);
}

void FragmentStore::reserve(std::size_t fragments, std::size_t vertices) {
  span_.reserve(fragments);
  source_.reserve(fragments);
  plane_.reserve(fragments);
  sphere_.reserve(fragments);
  pos_.reserve(vertices);
  if (tex_) uv_.reserve(vertices);
}

std::vector<std::uint32_t> FragmentStore::compact() {
  std::vector<std::uint32_t> to_new(span_.size(), 0);
  for (auto id : free_ids_) to_new[id] = kNone;
  FragmentStore out(tex_);
  out.reserve(span_.size() - free_ids_.size(), live_vertices_);
  for (std::uint32_t id = 0; id < span_.size(); ++id)
    if (to_new[id] != kNone) to_new[id] = out.add(view(id), plane_[id], sphere_[id]);
  out.side_tests_ = side_tests_;
  *this = std::move(out);
  return to_new;
}

void FragmentStore::drop_build_data() {
  free_memory(plane_);
  free_memory(sphere_);
  free_memory(free_ids_);
  free_memory(free_spans_);
}

FragmentView FragmentStore::view(std::uint32_t id) const {
  const Span s = span_[id];
  const std::span<const TexCoord> uv = tex_ ? std::span<const TexCoord>(uv_.data() + s.first, s.count)
                                            : std::span<const TexCoord>();
  return {points(id), uv, source_[id]};
}

FragmentStore::Parts FragmentStore::split(std::uint32_t id, const Plane& plane, double eps) {
  view(id).copy_to(whole_);
  const std::uint32_t support = plane_[id];
  release(id);
  const SplitKept kept = whole_.verts.size() == 2 ? split_segment_into(whole_, plane, eps, front_, back_)
                                                 : split_into(whole_, plane, eps, front_, back_);
  Parts parts;
  parts.dropped = kept.dropped;
  parts.dropped_area = kept.dropped_area;
  if (kept.front) parts.front = add(front_, support);
  if (kept.back) parts.back = add(back_, support);
  return parts;
}

SideCounts FragmentStore::count_sides(std::span<const std::uint32_t> ids, const Plane& p, double eps) const {
  SideCounts c;
  for (auto id : ids) {
    switch (classify(id, p, eps)) {
      case Side::Front: ++c.front; break;
      case Side::Back: ++c.back; break;
      case Side::Coplanar: ++c.coplanar; break;
      case Side::Spanning: ++c.spanning; break;
    }
  }
  return c;
}

void FragmentStore::count_sides(std::span<const std::uint32_t> ids, std::span<const Plane> planes, double eps,
                                std::span<SideCounts> out) const {
  assert(out.size() >= planes.size());
  for (std::size_t first = 0; first < planes.size(); first += kPlaneBlock) {
    const std::size_t k = std::min(kPlaneBlock, planes.size() - first);
    count_block(ids, planes.subspan(first, k), eps, out.subspan(first, k));
  }
}

namespace {

// The planes of a count_block call as arrays of their components, padded with zero planes to a
// multiple of four lanes, with a front and a back counter per plane. A zero plane never decides
// (0 - r > eps and 0 + r < -eps are false for r, eps >= 0) and its counters are never read. The
// counters are doubles, exact below 2^53, so a vector path adds its comparison mask ANDed with 1.0
// (AVX has no 256-bit integer add). Only the lanes the call uses are written: most nodes are
// small, count few planes, and would otherwise spend more on filling the block than on counting.
struct PlaneBlock {
  static constexpr std::size_t kSize = FragmentStore::kPlaneBlock;
  static_assert(kSize % 4 == 0, "whole groups of four lanes");
  alignas(32) double nx[kSize], ny[kSize], nz[kSize], d[kSize];
  alignas(32) double front[kSize], back[kSize];
  std::size_t k = 0;
  std::uint32_t all = 0;  // a bit per plane of the call

  explicit PlaneBlock(std::span<const Plane> planes)
      : k(planes.size()), all(planes.size() == kSize ? ~0u : (1u << planes.size()) - 1) {
    const std::size_t lanes = (k + 3) / 4 * 4;
    for (std::size_t j = 0; j < lanes; ++j) {
      const Plane p = j < k ? planes[j] : Plane{};
      nx[j] = p.n.x, ny[j] = p.n.y, nz[j] = p.n.z, d[j] = p.d;
      front[j] = back[j] = 0;
    }
  }
};

// Asks for the cache lines of a fragment's vertices, which the vertex pass reads for each plane
// its sphere straddles: that pass follows within a chunk, so the lines arrive while the other
// spheres are tested instead of one miss after another.
inline void prefetch_points(std::span<const Vec3> points) { prefetch_bytes(points.data(), points.size_bytes()); }

// Each path below tests every fragment's sphere against every plane of the block as classify()
// does, in Plane::distance's order, ((nx*cx + ny*cy) + nz*cz) + d, then dist - r > eps and
// dist + r < -eps, each rounded alike in a vector lane (no fused multiply-add), so all give the
// same bits; it counts the spheres decided and writes, per fragment, a bit per plane its sphere
// straddles (or whose distance is not a number: no comparison with NaN holds), which the vertex
// pass decides. `spheres` and `points` look a fragment up by id.

#if defined(__SSE2__)
// Two planes per instruction: SSE2 is the x86-64 baseline.
template <class Spheres, class Points>
void straddled_sse2(PlaneBlock& blk, Spheres spheres, Points points, std::span<const std::uint32_t> ids, double eps,
                    std::uint32_t* open) {
  const __m128d pos = _mm_set1_pd(eps), neg = _mm_set1_pd(-eps), one = _mm_set1_pd(1.0);
  for (std::size_t n = 0; n < ids.size(); ++n) {
    if (n + kPrefetchAhead < ids.size()) __builtin_prefetch(&spheres(ids[n + kPrefetchAhead]));
    const BoundingSphere& s = spheres(ids[n]);
    const __m128d cx = _mm_set1_pd(s.center.x), cy = _mm_set1_pd(s.center.y), cz = _mm_set1_pd(s.center.z);
    const __m128d r = _mm_set1_pd(s.radius);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; j += 2) {
      const __m128d dist = _mm_add_pd(
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_load_pd(blk.nx + j), cx), _mm_mul_pd(_mm_load_pd(blk.ny + j), cy)),
                     _mm_mul_pd(_mm_load_pd(blk.nz + j), cz)),
          _mm_load_pd(blk.d + j));
      const __m128d f = _mm_cmpgt_pd(_mm_sub_pd(dist, r), pos), b = _mm_cmplt_pd(_mm_add_pd(dist, r), neg);
      _mm_store_pd(blk.front + j, _mm_add_pd(_mm_load_pd(blk.front + j), _mm_and_pd(f, one)));
      _mm_store_pd(blk.back + j, _mm_add_pd(_mm_load_pd(blk.back + j), _mm_and_pd(b, one)));
      decided |= static_cast<std::uint32_t>(_mm_movemask_pd(_mm_or_pd(f, b))) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_points(points(ids[n]));
  }
}
#else
template <class Spheres, class Points>
void straddled_scalar(PlaneBlock& blk, Spheres spheres, Points points, std::span<const std::uint32_t> ids, double eps,
                      std::uint32_t* open) {
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const BoundingSphere& s = spheres(ids[n]);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; ++j) {
      const double dist = blk.nx[j] * s.center.x + blk.ny[j] * s.center.y + blk.nz[j] * s.center.z + blk.d[j];
      const bool f = dist - s.radius > eps, b = dist + s.radius < -eps;
      blk.front[j] += f;
      blk.back[j] += b;
      decided |= static_cast<std::uint32_t>(f || b) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_points(points(ids[n]));
  }
}
#endif

#if defined(__x86_64__) && defined(__GNUC__)
#define BSP_SPHERE_AVX 1
// Four planes per instruction where the processor has AVX (asked at run time: the build targets
// the x86-64 baseline). The same operations as straddled_sse2, lane for lane.
template <class Spheres, class Points>
__attribute__((target("avx"))) void straddled_avx(PlaneBlock& blk, Spheres spheres, Points points,
                                                  std::span<const std::uint32_t> ids, double eps, std::uint32_t* open) {
  const __m256d pos = _mm256_set1_pd(eps), neg = _mm256_set1_pd(-eps), one = _mm256_set1_pd(1.0);
  for (std::size_t n = 0; n < ids.size(); ++n) {
    if (n + kPrefetchAhead < ids.size()) __builtin_prefetch(&spheres(ids[n + kPrefetchAhead]));
    const BoundingSphere& s = spheres(ids[n]);
    const __m256d cx = _mm256_set1_pd(s.center.x), cy = _mm256_set1_pd(s.center.y), cz = _mm256_set1_pd(s.center.z);
    const __m256d r = _mm256_set1_pd(s.radius);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; j += 4) {
      const __m256d dist = _mm256_add_pd(
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_load_pd(blk.nx + j), cx),
                                      _mm256_mul_pd(_mm256_load_pd(blk.ny + j), cy)),
                        _mm256_mul_pd(_mm256_load_pd(blk.nz + j), cz)),
          _mm256_load_pd(blk.d + j));
      const __m256d f = _mm256_cmp_pd(_mm256_sub_pd(dist, r), pos, _CMP_GT_OQ);
      const __m256d b = _mm256_cmp_pd(_mm256_add_pd(dist, r), neg, _CMP_LT_OQ);
      _mm256_store_pd(blk.front + j, _mm256_add_pd(_mm256_load_pd(blk.front + j), _mm256_and_pd(f, one)));
      _mm256_store_pd(blk.back + j, _mm256_add_pd(_mm256_load_pd(blk.back + j), _mm256_and_pd(b, one)));
      decided |= static_cast<std::uint32_t>(_mm256_movemask_pd(_mm256_or_pd(f, b))) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_points(points(ids[n]));
  }
}
#endif

// The path asked for, as this processor runs it; all give the same bits.
template <class Spheres, class Points>
void straddled(VectorPath path, PlaneBlock& blk, Spheres spheres, Points points, std::span<const std::uint32_t> ids,
               double eps, std::uint32_t* open) {
#if defined(BSP_SPHERE_AVX)
  if (runs_avx(path)) return straddled_avx(blk, spheres, points, ids, eps, open);
#else
  (void)path;
#endif
#if defined(__SSE2__)
  straddled_sse2(blk, spheres, points, ids, eps, open);
#else
  straddled_scalar(blk, spheres, points, ids, eps, open);
#endif
}

}  // namespace

// Two passes per chunk of fragments: their spheres against the block (the vector loop, branch-free,
// which prefetches the vertices of the straddling), then the vertices of each fragment against each
// plane its sphere straddles.
void FragmentStore::count_block(std::span<const std::uint32_t> ids, std::span<const Plane> planes, double eps,
                                std::span<SideCounts> out) const {
  PlaneBlock block(planes);
  const auto spheres = [this](std::uint32_t id) -> const BoundingSphere& { return sphere_[id]; };
  const auto vertices = [this](std::uint32_t id) { return points(id); };
  std::uint32_t open[kCountChunk];
  for (std::size_t first = 0; first < ids.size(); first += kCountChunk) {
    const std::span<const std::uint32_t> chunk = ids.subspan(first, std::min(kCountChunk, ids.size() - first));
    straddled(vector_path_, block, spheres, vertices, chunk, eps, open);
    side_tests_ += block.k * chunk.size();
    for (std::size_t n = 0; n < chunk.size(); ++n)
      for (std::uint32_t straddling = open[n]; straddling != 0; straddling &= straddling - 1) {
        const auto j = static_cast<std::size_t>(std::countr_zero(straddling));
        side_tests_ += span_[chunk[n]].count;
        switch (bsp::classify(points(chunk[n]), planes[j], eps)) {
          case Side::Front: ++out[j].front; break;
          case Side::Back: ++out[j].back; break;
          case Side::Coplanar: ++out[j].coplanar; break;
          case Side::Spanning: ++out[j].spanning; break;
        }
      }
  }
  for (std::size_t j = 0; j < block.k; ++j) {
    out[j].front += static_cast<std::uint32_t>(block.front[j]);
    out[j].back += static_cast<std::uint32_t>(block.back[j]);
  }
}

bool is_convex_set(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                   const PlanePool& planes, double eps) {
  for (auto a : ids) {
    const Plane& pa = planes[frags.plane(a)];
    for (auto b : ids) {
      if (a == b) continue;
      const BoundingSphere& s = frags.sphere(b);
      if (pa.distance(s.center) - s.radius >= -eps) continue;
      if (!in_front_or_on(frags.points(b), pa, eps)) return false;
    }
  }
  return true;
}

}  // namespace bsp
