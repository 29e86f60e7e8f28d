#include "split/fragment_store.h"

#include <bit>
#include <cassert>
#include <limits>
#include <stdexcept>

#include "geometry/segment2.h"

#if defined(__SSE2__)
#include <emmintrin.h>
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

// The planes of a count_block call as arrays of their components, padded to an even count.
struct PlaneBlock {
  alignas(16) double nx[FragmentStore::kPlaneBlock], ny[FragmentStore::kPlaneBlock], nz[FragmentStore::kPlaneBlock],
      d[FragmentStore::kPlaneBlock];
  alignas(16) std::int64_t front[FragmentStore::kPlaneBlock] = {}, back[FragmentStore::kPlaneBlock] = {};
  std::size_t k = 0;

  explicit PlaneBlock(std::span<const Plane> planes) : k(planes.size()) {
    for (std::size_t j = 0; j < FragmentStore::kPlaneBlock; ++j) {
      const Plane p = j < k ? planes[j] : Plane{};
      nx[j] = p.n.x, ny[j] = p.n.y, nz[j] = p.n.z, d[j] = p.d;
    }
  }

  // Counts the planes the sphere is wholly in front of or behind; returns a bit per plane it
  // straddles (or whose distance is not a number), which classify's per-vertex path decides.
  std::uint32_t undecided_by_sphere(const BoundingSphere& s, double eps) {
#if defined(__SSE2__)
    // Two planes per instruction, in Plane::distance's order: ((nx*cx + ny*cy) + nz*cz) + d.
    const __m128d cx = _mm_set1_pd(s.center.x), cy = _mm_set1_pd(s.center.y), cz = _mm_set1_pd(s.center.z);
    const __m128d r = _mm_set1_pd(s.radius), pos = _mm_set1_pd(eps), neg = _mm_set1_pd(-eps);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < k; j += 2) {
      const __m128d dist = _mm_add_pd(
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_load_pd(nx + j), cx), _mm_mul_pd(_mm_load_pd(ny + j), cy)),
                     _mm_mul_pd(_mm_load_pd(nz + j), cz)),
          _mm_load_pd(d + j));
      const __m128d f = _mm_cmpgt_pd(_mm_sub_pd(dist, r), pos), b = _mm_cmplt_pd(_mm_add_pd(dist, r), neg);
      auto* fv = reinterpret_cast<__m128i*>(front + j);
      auto* bv = reinterpret_cast<__m128i*>(back + j);
      _mm_store_si128(fv, _mm_sub_epi64(_mm_load_si128(fv), _mm_castpd_si128(f)));  // a true lane is -1
      _mm_store_si128(bv, _mm_sub_epi64(_mm_load_si128(bv), _mm_castpd_si128(b)));
      decided |= static_cast<std::uint32_t>(_mm_movemask_pd(_mm_or_pd(f, b))) << j;
    }
#else
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < k; ++j) {
      const double dist = nx[j] * s.center.x + ny[j] * s.center.y + nz[j] * s.center.z + d[j];
      const bool f = dist - s.radius > eps, b = dist + s.radius < -eps;
      front[j] += f;
      back[j] += b;
      decided |= static_cast<std::uint32_t>(f || b) << j;
    }
#endif
    const std::uint32_t all = k == FragmentStore::kPlaneBlock ? ~0u : (1u << k) - 1;
    return ~decided & all;
  }
};

}  // namespace

// A padded lane (plane j >= k, all zero) may count; its counters are never read.
void FragmentStore::count_block(std::span<const std::uint32_t> ids, std::span<const Plane> planes, double eps,
                                std::span<SideCounts> out) const {
  PlaneBlock block(planes);
  for (auto id : ids) {
    side_tests_ += block.k;
    for (std::uint32_t open = block.undecided_by_sphere(sphere_[id], eps); open != 0; open &= open - 1) {
      const auto j = static_cast<std::size_t>(std::countr_zero(open));
      side_tests_ += span_[id].count;
      switch (bsp::classify(points(id), planes[j], eps)) {
        case Side::Front: ++block.front[j]; break;
        case Side::Back: ++block.back[j]; break;
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
