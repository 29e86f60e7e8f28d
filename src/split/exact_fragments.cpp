#include "split/exact_fragments.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <utility>

namespace bsp {

namespace {

// The rounded copy of a fragment: each vertex from its cofactors (x = C_0 / C_3 and so on, in grid
// units), an estimate for splitters only.
Polygon rounded_polygon(std::span<const VertexCofactors> cofactors, const Grid& grid, std::uint32_t source) {
  Polygon out;
  out.source = source;
  out.verts.reserve(cofactors.size());
  for (const VertexCofactors& c : cofactors)
    out.verts.push_back({grid.origin() + Vec3{c.c[0] / c.c[3], c.c[1] / c.c[3], c.c[2] / c.c[3]} * grid.step()});
  return out;
}

}  // namespace

std::uint32_t ExactFragments::store(PlanePolygon poly, std::vector<Vertex> verts) {
  std::vector<VertexCofactors> cofactors;
  cofactors.reserve(verts.size());
  for (const Vertex& v : verts) cofactors.push_back(v.cofactors);
  const std::uint32_t support = planes_.add(poly.support);
  const std::uint32_t id = rounded_.add(rounded_polygon(cofactors, planes_.grid(), poly.source), support);
  if (id >= poly_.size()) {
    poly_.resize(id + 1);
    verts_.resize(id + 1);
    box_.resize(id + 1);
  }
  box_[id] = filter_box(cofactors.data(), cofactors.size());
  poly_[id] = std::move(poly);
  verts_[id] = std::move(verts);
  return id;
}

std::uint32_t ExactFragments::add(PlanePolygon poly, std::span<const GridPoint> corners) {
  const std::size_t k = poly.size();
  std::vector<Vertex> verts(k);
  // Each plane rounded once (a 128-bit conversion is a library call), every vertex from those.
  const PlaneApprox support = approximate(poly.support);
  bounds_approx_.clear();
  for (const GridPlane& b : poly.bounds) bounds_approx_.push_back(approximate(b));
  for (std::size_t i = 0; i < k; ++i) {
    const auto c = vertex_cofactors(poly.support, poly.before(i), poly.after(i), support, bounds_approx_[i],
                                    bounds_approx_[(i + 1) % k], counters_.predicates);
    if (!c) throw std::invalid_argument("a plane polygon's vertex is not defined");
    verts[i].cofactors = *c;
    if (!corners.empty()) {
      verts[i].corner = corners[i];
      verts[i].on_grid = true;
    }
  }
  return store(std::move(poly), std::move(verts));
}

void ExactFragments::release(std::uint32_t id) {
  rounded_.release(id);
  poly_[id] = {};
  verts_[id] = {};
}

int ExactFragments::vertex_side(std::uint32_t id, std::size_t i, const GridPlane& plane, const PlaneApprox& approx) const {
  const Vertex& v = verts_[id][i];
  if (const auto f = detail::filtered_side(v.cofactors, approx); f.decided) {
    ++counters_.predicates.filtered;
    return f.sign;
  }
  if (v.on_grid) {
    ++counters_.on_grid;
    return plane.side(v.corner);
  }
  const PlanePolygon& poly = poly_[id];
  return side_of_vertex(poly.support, poly.before(i), poly.after(i), plane, counters_.predicates);
}

Side ExactFragments::sides(std::uint32_t id, std::uint32_t plane, bool all) const {
  if (PlanePool::coplanar(plane, rounded_.plane(id))) {
    ++counters_.coplanar_by_index;
    sides_.assign(poly_[id].size(), 0);
    return Side::Coplanar;
  }
  const PlaneApprox approx = planes_.approx(plane);
  if (const auto whole = detail::filtered_box_side(box_[id], approx); whole.decided) {
    ++counters_.boxes;
    sides_.assign(poly_[id].size(), whole.sign);
    return whole.sign > 0 ? Side::Front : Side::Back;
  }
  return vertex_sides(id, plane, approx, all);
}

Side ExactFragments::vertex_sides(std::uint32_t id, std::uint32_t plane, const PlaneApprox& approx, bool all) const {
  const std::size_t k = poly_[id].size();
  sides_.assign(k, 0);
  const GridPlane p = planes_[plane];
  bool front = false, back = false;
  for (std::size_t i = 0; i < k; ++i) {
    sides_[i] = vertex_side(id, i, p, approx);
    front |= sides_[i] > 0;
    back |= sides_[i] < 0;
    if (front && back && !all) return Side::Spanning;
  }
  if (front && back) return Side::Spanning;
  if (front) return Side::Front;
  if (back) return Side::Back;
  return Side::Coplanar;  // every vertex on a plane that is not its support: impossible for a polygon
}

Side ExactFragments::classify(std::uint32_t id, std::uint32_t plane) const { return sides(id, plane, false); }

namespace {

// The planes of one count_block call as arrays of their coefficients and magnitudes, padded to an
// even count, with a front and a back counter per plane (FragmentStore's PlaneBlock, for boxes).
struct BoxPlaneBlock {
  static constexpr std::size_t kSize = FragmentStore::kPlaneBlock;
  alignas(16) double a[kSize], b[kSize], c[kSize], d[kSize], qa[kSize], qb[kSize], qc[kSize], qd[kSize];
  alignas(16) std::int64_t front[kSize] = {}, back[kSize] = {};
  std::size_t k = 0;

  BoxPlaneBlock(const GridPlanePool& pool, std::span<const std::uint32_t> planes) : k(planes.size()) {
    for (std::size_t j = 0; j < kSize; ++j) {
      const PlaneApprox p = j < k ? pool.approx(planes[j]) : PlaneApprox{};
      a[j] = p.a, b[j] = p.b, c[j] = p.c, d[j] = p.d;
      qa[j] = std::abs(p.a), qb[j] = std::abs(p.b), qc[j] = std::abs(p.c), qd[j] = std::abs(p.d);
    }
  }

  // Counts the planes the box is wholly in front of or behind (detail::filtered_box_side, the same
  // operations in the same order, |a x| computed as |a| |x|, which rounds alike); returns a bit per
  // plane it leaves undecided.
  std::uint32_t undecided_by_box(const FilterBox& box) {
    const std::uint32_t all = k == kSize ? ~0u : (1u << k) - 1;
    if (!box.bounded) return all;
    std::uint32_t decided = 0;
#if defined(__SSE2__)
    const __m128d cx = _mm_set1_pd(box.centre[0]), cy = _mm_set1_pd(box.centre[1]), cz = _mm_set1_pd(box.centre[2]);
    const __m128d ax = _mm_set1_pd(std::abs(box.centre[0])), ay = _mm_set1_pd(std::abs(box.centre[1])),
                  az = _mm_set1_pd(std::abs(box.centre[2]));
    const __m128d hx = _mm_set1_pd(box.half[0]), hy = _mm_set1_pd(box.half[1]), hz = _mm_set1_pd(box.half[2]);
    const __m128d widen = _mm_set1_pd(1 + 0x1p-45), share = _mm_set1_pd(0x1p-45), zero = _mm_setzero_pd();
    for (std::size_t j = 0; j < k; j += 2) {
      const __m128d qa2 = _mm_load_pd(qa + j), qb2 = _mm_load_pd(qb + j), qc2 = _mm_load_pd(qc + j);
      const __m128d v = _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_load_pd(a + j), cx), _mm_mul_pd(_mm_load_pd(b + j), cy)),
                                              _mm_mul_pd(_mm_load_pd(c + j), cz)),
                                   _mm_load_pd(d + j));
      const __m128d s = _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(qa2, ax), _mm_mul_pd(qb2, ay)), _mm_mul_pd(qc2, az)),
                                   _mm_load_pd(qd + j));
      const __m128d r = _mm_add_pd(_mm_add_pd(_mm_mul_pd(qa2, hx), _mm_mul_pd(qb2, hy)), _mm_mul_pd(qc2, hz));
      const __m128d margin = _mm_add_pd(_mm_mul_pd(r, widen), _mm_mul_pd(share, s));
      const __m128d f = _mm_cmpgt_pd(v, margin), bk = _mm_cmplt_pd(v, _mm_sub_pd(zero, margin));
      auto* fv = reinterpret_cast<__m128i*>(front + j);
      auto* bv = reinterpret_cast<__m128i*>(back + j);
      _mm_store_si128(fv, _mm_sub_epi64(_mm_load_si128(fv), _mm_castpd_si128(f)));  // a true lane is -1
      _mm_store_si128(bv, _mm_sub_epi64(_mm_load_si128(bv), _mm_castpd_si128(bk)));
      decided |= static_cast<std::uint32_t>(_mm_movemask_pd(_mm_or_pd(f, bk))) << j;
    }
#else
    for (std::size_t j = 0; j < k; ++j) {
      const auto m = detail::filtered_box_side(box, {a[j], b[j], c[j], d[j]});
      front[j] += m.decided && m.sign > 0;
      back[j] += m.decided && m.sign < 0;
      decided |= static_cast<std::uint32_t>(m.decided) << j;
    }
#endif
    return ~decided & all;
  }
};

}  // namespace

void ExactFragments::count_sides(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                                 std::span<SideCounts> out) const {
  for (std::size_t first = 0; first < planes.size(); first += FragmentStore::kPlaneBlock) {
    const std::size_t k = std::min(FragmentStore::kPlaneBlock, planes.size() - first);
    count_block(ids, planes.subspan(first, k), out.subspan(first, k));
  }
}

// A padded lane (plane j >= k, all zero) never decides; its counters are never read.
void ExactFragments::count_block(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                                 std::span<SideCounts> out) const {
  BoxPlaneBlock block(planes_, planes);
  for (auto id : ids) {
    const std::uint32_t support = rounded_.plane(id);
    for (std::uint32_t open = block.undecided_by_box(box_[id]); open != 0; open &= open - 1) {
      const auto j = static_cast<std::size_t>(std::countr_zero(open));
      if (PlanePool::coplanar(planes[j], support)) {
        ++counters_.coplanar_by_index;
        ++out[j].coplanar;
        continue;
      }
      switch (vertex_sides(id, planes[j], planes_.approx(planes[j]), false)) {
        case Side::Front: ++out[j].front; break;
        case Side::Back: ++out[j].back; break;
        case Side::Coplanar: ++out[j].coplanar; break;
        case Side::Spanning: ++out[j].spanning; break;
      }
    }
  }
  std::uint64_t decided = 0;
  for (std::size_t j = 0; j < block.k; ++j) {
    out[j].front += static_cast<std::uint32_t>(block.front[j]);
    out[j].back += static_cast<std::uint32_t>(block.back[j]);
    decided += static_cast<std::uint64_t>(block.front[j] + block.back[j]);
  }
  counters_.boxes += decided;
}

std::uint32_t ExactFragments::add_part(PolygonPart part, const std::vector<Vertex>& from) {
  const PlanePolygon& poly = part.poly;
  std::vector<Vertex> verts(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) {
    if (part.origin[i] != kNewVertex) {
      verts[i] = from[part.origin[i]];
      continue;
    }
    const auto c = vertex_cofactors(poly.support, poly.before(i), poly.after(i), counters_.predicates);
    if (!c) throw std::logic_error("a split made an undefined vertex");
    verts[i].cofactors = *c;
  }
  return store(std::move(part.poly), std::move(verts));
}

PlanePolygon ExactFragments::take(std::uint32_t id) {
  PlanePolygon poly = std::move(poly_[id]);
  release(id);
  return poly;
}

ExactFragments::Parts ExactFragments::split(std::uint32_t id, std::uint32_t plane) {
  if (sides(id, plane, true) != Side::Spanning) throw std::logic_error("split of a fragment that does not span the plane");
  const std::vector<int> s = std::move(sides_);
  const GridPlane cut = planes_[plane];
  PolygonPart front = part_of(poly_[id], s, 1, cut);
  PolygonPart back = part_of(poly_[id], s, -1, cut);
  const std::vector<Vertex> from = std::move(verts_[id]);
  release(id);
  Parts parts;
  parts.front = add_part(std::move(front), from);
  parts.back = add_part(std::move(back), from);
  return parts;
}

}  // namespace bsp
