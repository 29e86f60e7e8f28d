#include "split/exact_fragments.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#include <utility>

namespace bsp {

namespace {

// A sphere no test can decide by (FragmentStore::classify falls through to the vertices): the
// copy's spheres serve the float kernel's side tests, and no splitter tests sides on the copy
// (SideCounter reads the exact fragments), so computing them would be wasted.
constexpr BoundingSphere kNoSphere{{0, 0, 0}, std::numeric_limits<double>::infinity()};

}  // namespace

// Each vertex from its cofactors (x = C_0 / C_3 and so on, in grid units) where C~_3 exceeds twice
// its error bound (filter_box's condition), else from its three planes (vertex_position). The
// condition keeps the quotient finite and of the right sign, not accurate: near it the error bound
// (e_abc + |x| e_d) / (C~_3 - e_d) can reach the coordinate's size. The copy only steers splitters'
// estimates (halving's points, naylor's measures); no side is decided on it.
void ExactFragments::rounded_polygon(PlaneRef support, std::uint32_t first, std::uint32_t count, std::uint32_t source,
                                     Polygon& out) const {
  const Grid& grid = planes_.grid();
  out.source = source;
  out.verts.clear();
  for (std::uint32_t i = 0; i < count; ++i) {
    const VertexCofactors& c = cof_[first + i];
    if (c.c[3] > 2 * c.error_d) {
      out.verts.push_back({grid.origin() + Vec3{c.c[0] / c.c[3], c.c[1] / c.c[3], c.c[2] / c.c[3]} * grid.step()});
      continue;
    }
    const auto p = vertex_position(plane_of(support), plane_of(bound_[first + i]), plane_of(bound_[first + (i + 1) % count]), grid);
    out.verts.push_back({p.value_or(grid.origin())});  // every vertex of a valid plane polygon is defined
  }
}

void ExactFragments::reserve(std::size_t fragments, std::size_t vertices, std::size_t input_fragments,
                             std::size_t input_vertices) {
  rounded_.reserve(fragments, vertices);
  own_.reserve(input_fragments + input_vertices);
  own_approx_.reserve(input_fragments + input_vertices);
  corners_.reserve(input_vertices);
  rec_.reserve(fragments);
  support_.reserve(fragments);
  bound_.reserve(vertices);
  cof_.reserve(vertices);
  corner_.reserve(vertices);
}

ExactFragments::PlaneRef ExactFragments::own(const GridPlane& p) {
  if (own_.size() >= kPooled) throw std::length_error("an exact build's input has more than 2^31 planes");
  own_.push_back(p);
  own_approx_.push_back(approximate(p));  // a 128-bit conversion is a library call: once per plane
  return static_cast<PlaneRef>(own_.size() - 1);
}

std::uint32_t ExactFragments::new_span(std::uint32_t count) {
  if (count < free_spans_.size() && !free_spans_[count].empty()) {
    const std::uint32_t first = free_spans_[count].back();
    free_spans_[count].pop_back();
    return first;
  }
  if (bound_.size() + count > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("a build's exact fragments have more than 2^32 vertices");
  const auto first = static_cast<std::uint32_t>(bound_.size());
  const std::size_t end = bound_.size() + count;
  bound_.resize(end);
  cof_.resize(end);
  corner_.resize(end);
  return first;
}

void ExactFragments::free_span(std::uint32_t first, std::uint32_t count) {
  if (count > reused_span_) return;  // rare, as in FragmentStore
  if (free_spans_.size() <= count) free_spans_.resize(count + 1);
  free_spans_[count].push_back(first);
}

FilterBox ExactFragments::box(std::uint32_t id) const {
  const Record& r = rec_[id];
  FilterBox b;
  for (int j = 0; j < 3; ++j) b.centre[j] = r.centre[j], b.half[j] = r.half[j];
  b.bounded = !std::isnan(r.half[0]);
  return b;
}

std::uint32_t ExactFragments::new_id(PlaneRef support, std::uint32_t pooled, std::uint32_t source,
                                     std::uint32_t first, std::uint32_t count) {
  vertices_live_ += count;
  if (copies_ == Copies::Rounded) {
    rounded_polygon(support, first, count, source, rounded_scratch_);
    return rounded_.add(rounded_scratch_, pooled, kNoSphere);
  }
  if (free_ids_.empty()) return static_cast<std::uint32_t>(rec_.size());
  const std::uint32_t id = free_ids_.back();
  free_ids_.pop_back();
  return id;
}

void ExactFragments::drop_id(std::uint32_t id) {
  vertices_live_ -= rec_[id].count;
  if (copies_ == Copies::Rounded) rounded_.release(id);
  else free_ids_.push_back(id);
}

std::uint32_t ExactFragments::store(PlaneRef support, std::uint32_t pooled, std::uint32_t source,
                                    std::uint32_t first, std::uint32_t count) {
  const std::span<const VertexCofactors> cofactors(cof_.data() + first, count);
  const std::uint32_t id = new_id(support, pooled, source, first, count);
  if (id >= rec_.size()) {
    rec_.resize(id + 1);
    support_.resize(id + 1);
  }
  const FilterBox b = filter_box(cofactors.data(), count);
  Record& r = rec_[id];
  for (int j = 0; j < 3; ++j) {
    r.centre[j] = b.bounded ? b.centre[j] : 0.0;
    r.half[j] = b.bounded ? b.half[j] : std::numeric_limits<double>::quiet_NaN();
  }
  r.support = pooled;
  r.first = first;
  r.count = count;
  r.source = source;
  support_[id] = support;
  return id;
}

static_assert(kGridBits < 53, "grid coordinates are exact in doubles");

std::uint32_t ExactFragments::add(const PlanePolygon& poly, std::span<const GridPoint> corners) {
  const auto k = static_cast<std::uint32_t>(poly.size());
  const std::uint32_t first = new_span(k);
  const PlaneRef support = own(poly.support);
  for (std::uint32_t i = 0; i < k; ++i) bound_[first + i] = own(poly.bounds[i]);
  for (std::uint32_t i = 0; i < k; ++i) {
    corner_[first + i] = kNoCorner;
    if (!corners.empty()) {
      // An input corner is a grid point, below 2^kGridBits in each coordinate, so exact in doubles:
      // its cofactors are its coordinates with weight 1, without error (any positive multiple of
      // the homogeneous point will do).
      const GridPoint& q = corners[i];
      cof_[first + i] = {{static_cast<double>(q.x), static_cast<double>(q.y), static_cast<double>(q.z), 1.0}, 0.0, 0.0};
      corner_[first + i] = static_cast<std::uint32_t>(corners_.size());
      corners_.push_back(q);
      continue;
    }
    const PlaneRef before = bound_[first + i], after = bound_[first + (i + 1) % k];
    const auto c = vertex_cofactors(poly.support, own_[before], own_[after], own_approx_[support], own_approx_[before],
                                    own_approx_[after], counters_.predicates);
    if (!c) throw std::invalid_argument("a plane polygon's vertex is not defined");
    cof_[first + i] = *c;
  }
  return store(support, planes_.add(poly.support), poly.source, first, k);
}

std::uint32_t ExactFragments::add_pooled(std::uint32_t support, std::span<const std::uint32_t> bounds,
                                        std::uint32_t source) {
  if (support >= kPooled || planes_.size() > kPooled) throw std::length_error("more than 2^31 pooled planes");
  const auto k = static_cast<std::uint32_t>(bounds.size());
  const std::uint32_t first = new_span(k);
  const PlaneRef s = kPooled | support;
  for (std::uint32_t i = 0; i < k; ++i) bound_[first + i] = kPooled | bounds[i];
  for (std::uint32_t i = 0; i < k; ++i) {
    const PlaneRef before = bound_[first + i], after = bound_[first + (i + 1) % k];
    const auto c = vertex_cofactors(plane_of(s), plane_of(before), plane_of(after), approx_of(s), approx_of(before),
                                    approx_of(after), counters_.predicates);
    if (!c) throw std::invalid_argument("a plane polygon's vertex is not defined");
    cof_[first + i] = *c;
    corner_[first + i] = kNoCorner;
  }
  return store(s, support, source, first, k);
}

void ExactFragments::release(std::uint32_t id) {
  drop_id(id);
  free_span(rec_[id].first, rec_[id].count);
}

PlanePolygon ExactFragments::polygon(std::uint32_t id) const {
  const Record& r = rec_[id];
  PlanePolygon out{plane_of(support_[id]), {}, r.source};
  out.bounds.reserve(r.count);
  for (std::uint32_t i = 0; i < r.count; ++i) out.bounds.push_back(plane_of(bound_[r.first + i]));
  return out;
}

int ExactFragments::vertex_side(std::uint32_t id, std::size_t i, std::uint32_t pooled, const GridPlane& plane,
                                const PlaneApprox& approx) const {
  const std::size_t slot = rec_[id].first + i;
  if (const auto f = detail::filtered_side(cof_[slot], approx); f.decided) {
    ++counters_.predicates.filtered;
    return f.sign;
  }
  if (corner_[slot] != kNoCorner) {
    ++counters_.on_grid;
    return plane.side(corners_[corner_[slot]]);
  }
  const Record& r = rec_[id];
  const PlaneRef before = bound_[slot], after = bound_[r.first + (i + 1) % r.count];
  // A vertex a cut made lies on the cut: a merge tests its pieces against that plane again, and
  // the filter cannot decide a zero. Pooled planes are canonical, so equal indices are equal planes.
  if (on_pooled(before, pooled) || on_pooled(after, pooled)) {
    ++counters_.on_bound;
    return 0;
  }
  return side_of_vertex(plane_of(support_[id]), plane_of(before), plane_of(after), plane, counters_.predicates);
}

Side ExactFragments::classify(std::uint32_t id, std::uint32_t plane) const {
  const Record& r = rec_[id];
  if (PlanePool::coplanar(plane, r.support)) {
    ++counters_.coplanar_by_index;
    return Side::Coplanar;
  }
  const PlaneApprox approx = planes_.approx(plane);
  if (const auto whole = detail::filtered_box_side(box(id), approx); whole.decided) {
    ++counters_.boxes;
    return whole.sign > 0 ? Side::Front : Side::Back;
  }
  return vertex_sides(id, plane, approx, nullptr);
}

// The filter decides nearly every vertex: its loop runs over the cofactors alone, and the plane's
// integers are fetched only for the first vertex it leaves undecided (vertex_side then takes the rest).
Side ExactFragments::vertex_sides(std::uint32_t id, std::uint32_t plane, const PlaneApprox& approx, int* sides) const {
  const Record& r = rec_[id];
  const VertexCofactors* cof = cof_.data() + r.first;
  bool front = false, back = false;
  std::uint32_t i = 0;
  for (; i < r.count; ++i) {
    const auto f = detail::filtered_side(cof[i], approx);
    if (!f.decided) break;
    if (sides) sides[i] = f.sign;
    front |= f.sign > 0;
    back |= f.sign < 0;
    if (front && back && !sides) {
      counters_.predicates.filtered += i + 1;
      return Side::Spanning;
    }
  }
  counters_.predicates.filtered += i;
  if (i < r.count) {
    const GridPlane p = planes_[plane];
    for (; i < r.count; ++i) {
      const int s = vertex_side(id, i, plane, p, approx);
      if (sides) sides[i] = s;
      front |= s > 0;
      back |= s < 0;
      if (front && back && !sides) return Side::Spanning;
    }
  }
  if (front && back) return Side::Spanning;
  if (front) return Side::Front;
  if (back) return Side::Back;
  return Side::Coplanar;  // every vertex on a plane that is not its support: impossible for a polygon
}

namespace {

// The planes of one count_block call as arrays of their coefficients and magnitudes, padded with
// zero planes (which never decide: 0 > 0 is false) to a multiple of four lanes, with a front and a
// back counter per plane (FragmentStore's PlaneBlock, for boxes). The counters are doubles, exact
// below 2^53, so that a vector path adds its comparison mask ANDed with 1.0. Only the lanes the
// call uses are written (most nodes are small and count few planes).
struct BoxPlaneBlock {
  static constexpr std::size_t kSize = FragmentStore::kPlaneBlock;
  static_assert(kSize % 4 == 0, "whole groups of four lanes");
  alignas(32) double a[kSize], b[kSize], c[kSize], d[kSize], qa[kSize], qb[kSize], qc[kSize], qd[kSize];
  alignas(32) double front[kSize], back[kSize];
  std::size_t k = 0;
  std::uint32_t all = 0;  // a bit per plane of the call

  BoxPlaneBlock(const GridPlanePool& pool, std::span<const std::uint32_t> planes)
      : k(planes.size()), all(planes.size() == kSize ? ~0u : (1u << planes.size()) - 1) {
    const std::size_t lanes = (k + 3) / 4 * 4;
    for (std::size_t j = 0; j < lanes; ++j) {
      const PlaneApprox p = j < k ? pool.approx(planes[j]) : PlaneApprox{};
      a[j] = p.a, b[j] = p.b, c[j] = p.c, d[j] = p.d;
      qa[j] = std::abs(p.a), qb[j] = std::abs(p.b), qc[j] = std::abs(p.c), qd[j] = std::abs(p.d);
      front[j] = back[j] = 0;
    }
  }
};

using Record = ExactFragments::Record;

// Asks for the cache lines of a fragment's vertex cofactors, which the exact pass of count_block
// reads for each plane its box leaves undecided: that pass follows within a chunk, so the lines
// arrive while the other boxes are tested instead of one miss after another.
inline void prefetch_vertices(const VertexCofactors* v, std::uint32_t count) {
  prefetch_bytes(v, count * sizeof(VertexCofactors));
}

// Each path below tests every fragment's box against every plane of the block as
// detail::filtered_box_side does, the same operations in the same order (|a x| computed as |a| |x|,
// which rounds alike; no fused multiply-add), so all give the same bits; it counts the boxes
// decided and writes, per fragment, a bit per plane its box leaves undecided. An unbounded box's
// NaN half-widths make every margin NaN, so no lane decides.

#if defined(__SSE2__)
// Two planes per instruction: SSE2 is the x86-64 baseline.
void undecided_sse2(BoxPlaneBlock& blk, const Record* rec, const VertexCofactors* cof, std::span<const std::uint32_t> ids,
                    std::uint32_t* open) {
  const __m128d widen = _mm_set1_pd(1 + 0x1p-45), share = _mm_set1_pd(0x1p-45), zero = _mm_setzero_pd(),
                one = _mm_set1_pd(1.0);
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const Record& box = rec[ids[n]];
    const __m128d cx = _mm_set1_pd(box.centre[0]), cy = _mm_set1_pd(box.centre[1]), cz = _mm_set1_pd(box.centre[2]);
    const __m128d ax = _mm_set1_pd(std::abs(box.centre[0])), ay = _mm_set1_pd(std::abs(box.centre[1])),
                  az = _mm_set1_pd(std::abs(box.centre[2]));
    const __m128d hx = _mm_set1_pd(box.half[0]), hy = _mm_set1_pd(box.half[1]), hz = _mm_set1_pd(box.half[2]);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; j += 2) {
      const __m128d qa = _mm_load_pd(blk.qa + j), qb = _mm_load_pd(blk.qb + j), qc = _mm_load_pd(blk.qc + j);
      const __m128d v = _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_load_pd(blk.a + j), cx),
                                                         _mm_mul_pd(_mm_load_pd(blk.b + j), cy)),
                                              _mm_mul_pd(_mm_load_pd(blk.c + j), cz)),
                                   _mm_load_pd(blk.d + j));
      const __m128d s = _mm_add_pd(_mm_add_pd(_mm_add_pd(_mm_mul_pd(qa, ax), _mm_mul_pd(qb, ay)), _mm_mul_pd(qc, az)),
                                   _mm_load_pd(blk.qd + j));
      const __m128d r = _mm_add_pd(_mm_add_pd(_mm_mul_pd(qa, hx), _mm_mul_pd(qb, hy)), _mm_mul_pd(qc, hz));
      const __m128d margin = _mm_add_pd(_mm_mul_pd(r, widen), _mm_mul_pd(share, s));
      const __m128d f = _mm_cmpgt_pd(v, margin), bk = _mm_cmplt_pd(v, _mm_sub_pd(zero, margin));
      _mm_store_pd(blk.front + j, _mm_add_pd(_mm_load_pd(blk.front + j), _mm_and_pd(f, one)));
      _mm_store_pd(blk.back + j, _mm_add_pd(_mm_load_pd(blk.back + j), _mm_and_pd(bk, one)));
      decided |= static_cast<std::uint32_t>(_mm_movemask_pd(_mm_or_pd(f, bk))) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_vertices(cof + box.first, box.count);
  }
}
#else
void undecided_scalar(BoxPlaneBlock& blk, const Record* rec, const VertexCofactors* cof, std::span<const std::uint32_t> ids,
                      std::uint32_t* open) {
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const Record& r = rec[ids[n]];
    const FilterBox box{{r.centre[0], r.centre[1], r.centre[2]}, {r.half[0], r.half[1], r.half[2]}, !std::isnan(r.half[0])};
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; ++j) {
      const auto m = detail::filtered_box_side(box, {blk.a[j], blk.b[j], blk.c[j], blk.d[j]});
      blk.front[j] += m.decided && m.sign > 0;
      blk.back[j] += m.decided && m.sign < 0;
      decided |= static_cast<std::uint32_t>(m.decided) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_vertices(cof + r.first, r.count);
  }
}
#endif

#if defined(__x86_64__) && defined(__GNUC__)
#define BSP_BOX_AVX 1
// Four planes per instruction where the processor has AVX (asked at run time: the build targets
// the x86-64 baseline). The same operations as undecided_sse2, lane for lane.
__attribute__((target("avx"))) void undecided_avx(BoxPlaneBlock& blk, const Record* rec, const VertexCofactors* cof,
                                                  std::span<const std::uint32_t> ids, std::uint32_t* open) {
  const __m256d widen = _mm256_set1_pd(1 + 0x1p-45), share = _mm256_set1_pd(0x1p-45), zero = _mm256_setzero_pd(),
                one = _mm256_set1_pd(1.0);
  for (std::size_t n = 0; n < ids.size(); ++n) {
    const Record& box = rec[ids[n]];
    const __m256d cx = _mm256_set1_pd(box.centre[0]), cy = _mm256_set1_pd(box.centre[1]),
                  cz = _mm256_set1_pd(box.centre[2]);
    const __m256d ax = _mm256_set1_pd(std::abs(box.centre[0])), ay = _mm256_set1_pd(std::abs(box.centre[1])),
                  az = _mm256_set1_pd(std::abs(box.centre[2]));
    const __m256d hx = _mm256_set1_pd(box.half[0]), hy = _mm256_set1_pd(box.half[1]), hz = _mm256_set1_pd(box.half[2]);
    std::uint32_t decided = 0;
    for (std::size_t j = 0; j < blk.k; j += 4) {
      const __m256d qa = _mm256_load_pd(blk.qa + j), qb = _mm256_load_pd(blk.qb + j), qc = _mm256_load_pd(blk.qc + j);
      const __m256d v = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(_mm256_load_pd(blk.a + j), cx),
                                                                  _mm256_mul_pd(_mm256_load_pd(blk.b + j), cy)),
                                                    _mm256_mul_pd(_mm256_load_pd(blk.c + j), cz)),
                                      _mm256_load_pd(blk.d + j));
      const __m256d s = _mm256_add_pd(
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(qa, ax), _mm256_mul_pd(qb, ay)), _mm256_mul_pd(qc, az)),
          _mm256_load_pd(blk.qd + j));
      const __m256d r = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(qa, hx), _mm256_mul_pd(qb, hy)), _mm256_mul_pd(qc, hz));
      const __m256d margin = _mm256_add_pd(_mm256_mul_pd(r, widen), _mm256_mul_pd(share, s));
      const __m256d f = _mm256_cmp_pd(v, margin, _CMP_GT_OQ);
      const __m256d bk = _mm256_cmp_pd(v, _mm256_sub_pd(zero, margin), _CMP_LT_OQ);
      _mm256_store_pd(blk.front + j, _mm256_add_pd(_mm256_load_pd(blk.front + j), _mm256_and_pd(f, one)));
      _mm256_store_pd(blk.back + j, _mm256_add_pd(_mm256_load_pd(blk.back + j), _mm256_and_pd(bk, one)));
      decided |= static_cast<std::uint32_t>(_mm256_movemask_pd(_mm256_or_pd(f, bk))) << j;
    }
    open[n] = ~decided & blk.all;
    if (open[n] != 0) prefetch_vertices(cof + box.first, box.count);
  }
}
#endif

// The path asked for, as this processor runs it; all give the same bits.
void undecided_by_box(VectorPath path, BoxPlaneBlock& blk, const Record* rec, const VertexCofactors* cof,
                      std::span<const std::uint32_t> ids, std::uint32_t* open) {
#if defined(BSP_BOX_AVX)
  if (runs_avx(path)) return undecided_avx(blk, rec, cof, ids, open);
#else
  (void)path;
#endif
#if defined(__SSE2__)
  undecided_sse2(blk, rec, cof, ids, open);
#else
  undecided_scalar(blk, rec, cof, ids, open);
#endif
}

}  // namespace

void ExactFragments::count_sides(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                                 std::span<SideCounts> out) const {
  for (std::size_t first = 0; first < planes.size(); first += FragmentStore::kPlaneBlock) {
    const std::size_t k = std::min(FragmentStore::kPlaneBlock, planes.size() - first);
    count_block(ids, planes.subspan(first, k), out.subspan(first, k));
  }
}

// Two passes per chunk of fragments: their boxes against the block (the vector loop, branch-free,
// which prefetches the vertices of the undecided), then the vertices of each fragment against each
// plane its box left undecided. A padded lane (plane j >= k, all zero) never decides; its counters
// are never read.
void ExactFragments::count_block(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                                 std::span<SideCounts> out) const {
  BoxPlaneBlock block(planes_, planes);
  std::uint32_t open[FragmentStore::kCountChunk];
  for (std::size_t first = 0; first < ids.size(); first += FragmentStore::kCountChunk) {
    const std::span<const std::uint32_t> chunk =
        ids.subspan(first, std::min(FragmentStore::kCountChunk, ids.size() - first));
    undecided_by_box(vector_path_, block, rec_.data(), cof_.data(), chunk, open);
    for (std::size_t n = 0; n < chunk.size(); ++n)
      if (open[n] != 0) count_vertices(chunk[n], open[n], planes, out);
  }
  std::uint64_t decided = 0;
  for (std::size_t j = 0; j < block.k; ++j) {
    const auto front = static_cast<std::uint32_t>(block.front[j]), back = static_cast<std::uint32_t>(block.back[j]);
    out[j].front += front;
    out[j].back += back;
    decided += std::uint64_t{front} + back;
  }
  counters_.boxes += decided;
}

void ExactFragments::count_vertices(std::uint32_t id, std::uint32_t open, std::span<const std::uint32_t> planes,
                                    std::span<SideCounts> out) const {
  const std::uint32_t support = rec_[id].support;
  for (; open != 0; open &= open - 1) {
    const auto j = static_cast<std::size_t>(std::countr_zero(open));
    if (PlanePool::coplanar(planes[j], support)) {
      ++counters_.coplanar_by_index;
      ++out[j].coplanar;
      continue;
    }
    switch (vertex_sides(id, planes[j], planes_.approx(planes[j]), nullptr)) {
      case Side::Front: ++out[j].front; break;
      case Side::Back: ++out[j].back; break;
      case Side::Coplanar: ++out[j].coplanar; break;
      case Side::Spanning: ++out[j].spanning; break;
    }
  }
}

std::uint32_t ExactFragments::add_part(PlaneRef support, std::uint32_t pooled, std::uint32_t source,
                                       std::uint32_t from, PlaneRef cut) {
  const auto m = static_cast<std::uint32_t>(kept_.size());  // kept edges; the cut is bound m
  const std::uint32_t first = new_span(m + 1);              // may move the arrays: slots, not pointers
  for (std::uint32_t i = 0; i < m; ++i) {
    const std::uint32_t j = kept_[i];
    bound_[first + i] = bound_[from + j];
    cof_[first + i] = cof_[from + j];  // the parent's vertex j (kept_edges); vertex m - 1 is replaced below
    corner_[first + i] = corner_[from + j];
  }
  bound_[first + m] = cut;
  // The new vertices: where the last kept edge meets the cut, and the cut the first kept edge.
  const GridPlane s = plane_of(support);
  const PlaneApprox sa = approx_of(support);
  for (const std::uint32_t i : {m - 1, m}) {
    const PlaneRef before = bound_[first + i], after = bound_[first + (i + 1) % (m + 1)];
    const auto c = vertex_cofactors(s, plane_of(before), plane_of(after), sa, approx_of(before), approx_of(after),
                                    counters_.predicates);
    if (!c) throw std::logic_error("a split made an undefined vertex");
    cof_[first + i] = *c;
    corner_[first + i] = kNoCorner;
  }
  return store(support, pooled, source, first, m + 1);
}

void ExactFragments::take_into(std::uint32_t id, PlanePolygonSet& out) {
  const Record& r = rec_[id];
  out.push_back(support_[id], std::span<const PlaneRef>(bound_.data() + r.first, r.count), r.source);
  release(id);
}

std::uint32_t ExactFragments::clip(std::uint32_t id, std::uint32_t plane, bool keep_parent) {
  const Record& r = rec_[id];
  if (PlanePool::coplanar(plane, r.support)) {
    ++counters_.coplanar_by_index;
    return id;
  }
  const auto behind = [&] {
    if (!keep_parent) release(id);
    return FragmentStore::kNone;
  };
  const PlaneApprox approx = planes_.approx(plane);
  if (const auto whole = detail::filtered_box_side(box(id), approx); whole.decided) {
    ++counters_.boxes;
    return whole.sign > 0 ? id : behind();
  }
  sides_.resize(r.count);
  switch (vertex_sides(id, plane, approx, sides_.data())) {
    case Side::Front:
    case Side::Coplanar: return id;
    case Side::Back: return behind();
    case Side::Spanning: break;
  }
  if (plane >= kPooled) throw std::length_error("an exact build pooled more than 2^31 planes");
  const PlaneRef support = support_[id];
  const std::uint32_t pooled = r.support, source = r.source, from = r.first, k = r.count;
  if (!keep_parent) drop_id(id);
  kept_edges(sides_, 1, kept_);
  const std::uint32_t front = add_part(support, pooled, source, from, kPooled | plane);
  if (!keep_parent) free_span(from, k);
  return front;
}

// The parent's slots are freed only after both parts are written, so neither part's run can be the
// one it copies from; its id goes first, as FragmentStore::split releases before adding.
ExactFragments::Parts ExactFragments::split(std::uint32_t id, std::uint32_t plane, bool keep_parent) {
  // A spanning fragment is neither coplanar nor decided by its box: only its vertices are tested.
  sides_.resize(rec_[id].count);
  if (PlanePool::coplanar(plane, rec_[id].support) ||
      vertex_sides(id, plane, planes_.approx(plane), sides_.data()) != Side::Spanning)
    throw std::logic_error("split of a fragment that does not span the plane");
  if (plane >= kPooled) throw std::length_error("an exact build pooled more than 2^31 planes");
  const PlaneRef cut = kPooled | plane, opposite = kPooled | PlanePool::flip(plane);
  const PlaneRef support = support_[id];
  const std::uint32_t pooled = rec_[id].support, source = rec_[id].source;
  const std::uint32_t from = rec_[id].first, k = rec_[id].count;
  if (!keep_parent) drop_id(id);
  Parts parts;
  kept_edges(sides_, 1, kept_);
  parts.front = add_part(support, pooled, source, from, cut);
  kept_edges(sides_, -1, kept_);
  parts.back = add_part(support, pooled, source, from, opposite);
  if (!keep_parent) free_span(from, k);
  return parts;
}

}  // namespace bsp
