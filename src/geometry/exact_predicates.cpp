#include "geometry/exact_predicates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bsp {

namespace {

using Exact = WideInt<7>;
template <class T, int K>
using Matrix = std::array<std::array<T, K>, K>;

// The expansion whose rounding errors the filter counts: along the first column, sums left to
// right. With kPermanent every minus becomes a plus (the permanent of non-negative entries).
template <class T, bool kPermanent>
T combine(const T& x, const T& y) {
  if constexpr (kPermanent) return x + y;
  else return x - y;
}

template <class T, bool kPermanent>
T det2(const T& a, const T& b, const T& c, const T& d) {
  return combine<T, kPermanent>(a * d, c * b);
}

template <class T, bool kPermanent>
T det3(const Matrix<T, 3>& m) {
  const T t0 = m[0][0] * det2<T, kPermanent>(m[1][1], m[1][2], m[2][1], m[2][2]);
  const T t1 = m[1][0] * det2<T, kPermanent>(m[0][1], m[0][2], m[2][1], m[2][2]);
  const T t2 = m[2][0] * det2<T, kPermanent>(m[0][1], m[0][2], m[1][1], m[1][2]);
  return combine<T, kPermanent>(t0, t1) + t2;
}

// The 3x3 minor of m without row `skip` and column 0.
template <class T>
Matrix<T, 3> minor_of(const Matrix<T, 4>& m, int skip) {
  Matrix<T, 3> out{};
  for (int i = 0, r = 0; i < 4; ++i) {
    if (i == skip) continue;
    out[r++] = {m[i][1], m[i][2], m[i][3]};
  }
  return out;
}

template <class T, bool kPermanent>
T det4(const Matrix<T, 4>& m) {
  const T t0 = m[0][0] * det3<T, kPermanent>(minor_of(m, 0));
  const T t1 = m[1][0] * det3<T, kPermanent>(minor_of(m, 1));
  const T t2 = m[2][0] * det3<T, kPermanent>(minor_of(m, 2));
  const T t3 = m[3][0] * det3<T, kPermanent>(minor_of(m, 3));
  return combine<T, kPermanent>(combine<T, kPermanent>(t0, t1) + t2, t3);
}

template <class T, class Convert>
Matrix<T, 3> normals(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, Convert f) {
  Matrix<T, 3> m{};
  const GridPlane* p[] = {&p1, &p2, &p3};
  for (int i = 0; i < 3; ++i) m[i] = {f(p[i]->a), f(p[i]->b), f(p[i]->c)};
  return m;
}

template <class T, class Convert>
Matrix<T, 4> planes(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4, Convert f) {
  Matrix<T, 4> m{};
  const GridPlane* p[] = {&p1, &p2, &p3, &p4};
  for (int i = 0; i < 4; ++i) m[i] = {f(p[i]->a), f(p[i]->b), f(p[i]->c), f(p[i]->d)};
  return m;
}

// Each conversion rounds once, to nearest. A value that fits 64 bits (most normals' coefficients)
// takes the one-instruction conversion, which rounds the same; the 128-bit one is a library call.
double to_double(Int128 v) {
  const auto low = static_cast<std::int64_t>(v);
  return low == v ? static_cast<double>(low) : static_cast<double>(v);
}
double to_magnitude(Int128 v) { return std::abs(to_double(v)); }
Exact to_exact(Int128 v) { return Exact(v); }

// The exact fallback's widths (bounds in the header): a normal coefficient fits Int128; a 2x2
// minor of normals, below 2^167, fits 3 limbs; det N, below 2^252, fits 4; d det N, below 2^377,
// and the sum of four of them, below 2^379, fit 6.
using NormalMinor2 = WideInt<3>;
using NormalMinor3 = WideInt<4>;
using OffsetTimesMinor = WideInt<6>;
static_assert(kNormalBits + kNormalBits + 1 < 64 * 3 - 1);
static_assert(kNormalBits + kNormalBits + 1 + kNormalBits + 2 < 64 * 4 - 1);
static_assert(kOffsetBits + (3 * kNormalBits + 3) + 2 < 64 * 6 - 1);

// det of the normals of rows r0, r1, r2 of p, along the first column.
NormalMinor3 narrow_normals_det(const GridPlane* const* p, int r0, int r1, int r2) {
  const auto minor2 = [&](int i, int j) {  // of columns (b, c), rows i and j
    return NormalMinor2(p[i]->b) * NormalMinor2(p[j]->c) - NormalMinor2(p[j]->b) * NormalMinor2(p[i]->c);
  };
  const auto term = [&](int i, int j, int k) { return NormalMinor3(p[i]->a) * NormalMinor3(minor2(j, k)); };
  return (term(r0, r1, r2) - term(r1, r0, r2)) + term(r2, r0, r1);
}

detail::MaybeSign decide(double det, double permanent, int roundings) {
  if (permanent == 0) return {true, 0};
  // (m + 1) * 2^-53 is exact; the product rounds once, which the bound allows for.
  const double threshold = (roundings + 1) * 0x1p-53 * permanent;
  if (det > threshold) return {true, 1};
  if (det < -threshold) return {true, -1};
  return {false, 0};
}

}  // namespace

namespace detail {

MaybeSign filtered_normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3) {
  const double det = det3<double, false>(normals<double>(p1, p2, p3, to_double));
  const double permanent = det3<double, true>(normals<double>(p1, p2, p3, to_magnitude));
  return decide(det, permanent, kFilterRoundings3);
}

MaybeSign filtered_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4) {
  const double det = det4<double, false>(planes<double>(p1, p2, p3, p4, to_double));
  const double permanent = det4<double, true>(planes<double>(p1, p2, p3, p4, to_magnitude));
  return decide(det, permanent, kFilterRoundings4);
}

int exact_normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3) {
  const GridPlane* p[] = {&p1, &p2, &p3};
  return narrow_normals_det(p, 0, 1, 2).sign();
}

// Along the offset column: det M = sum over i of (-1)^(i + 3) d_i det N_i, N_i the normals
// without row i, each in the narrowest width that holds it (see the header).
int exact_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4) {
  const GridPlane* p[] = {&p1, &p2, &p3, &p4};
  const auto term = [&](int i, int r0, int r1, int r2) {
    return OffsetTimesMinor(p[i]->d) * OffsetTimesMinor(narrow_normals_det(p, r0, r1, r2));
  };
  return ((term(1, 0, 2, 3) - term(0, 1, 2, 3)) + (term(3, 0, 1, 2) - term(2, 0, 1, 3))).sign();
}

}  // namespace detail

int normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, PredicateCounters& counters) {
  if (const auto f = detail::filtered_normals_sign(p1, p2, p3); f.decided) {
    ++counters.filtered;
    return f.sign;
  }
  ++counters.exact;
  return detail::exact_normals_sign(p1, p2, p3);
}

int planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4,
                PredicateCounters& counters) {
  if (const auto f = detail::filtered_planes_sign(p1, p2, p3, p4); f.decided) {
    ++counters.filtered;
    return f.sign;
  }
  ++counters.exact;
  return detail::exact_planes_sign(p1, p2, p3, p4);
}

PlaneApprox approximate(const GridPlane& p) { return {to_double(p.a), to_double(p.b), to_double(p.c), to_double(p.d)}; }

std::optional<VertexCofactors> vertex_cofactors(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3,
                                                PredicateCounters& counters) {
  return vertex_cofactors(p1, p2, p3, approximate(p1), approximate(p2), approximate(p3), counters);
}

std::optional<VertexCofactors> vertex_cofactors(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3,
                                                const PlaneApprox& a1, const PlaneApprox& a2, const PlaneApprox& a3,
                                                PredicateCounters& counters) {
  // Rows (a, b, c, d) rounded once each; the magnitudes are the rounded values' (rounding to
  // nearest is symmetric, so |fl(x)| = fl(|x|), as to_magnitude computes them).
  const PlaneApprox* rows[] = {&a1, &a2, &a3};
  Matrix<double, 4> m{}, mag{};
  for (int i = 0; i < 3; ++i) {
    m[i] = {rows[i]->a, rows[i]->b, rows[i]->c, rows[i]->d};
    for (int j = 0; j < 4; ++j) mag[i][j] = std::abs(m[i][j]);
  }
  // The minor of rows 0..2 without column `skip`, in the column order the expansion above uses.
  const auto minor = [](const Matrix<double, 4>& a, int skip) {
    Matrix<double, 3> out{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0, k = 0; j < 4; ++j)
        if (j != skip) out[i][k++] = a[i][j];
    return out;
  };
  VertexCofactors v;
  double permanent_n = 0;
  for (int j = 0; j < 4; ++j) {
    v.c[j] = ((3 + j) % 2 == 0 ? 1.0 : -1.0) * det3<double, false>(minor(m, j));  // (-1)^(3 + j) minor
    const double permanent = det3<double, true>(minor(mag, j));
    const double error = (kFilterRoundings3 + 1) * 0x1p-53 * permanent;
    (j == 3 ? v.error_d : v.error_abc) = std::max(j == 3 ? v.error_d : v.error_abc, error);
    if (j == 3) permanent_n = permanent;
  }
  // C_3 is det N computed as filtered_normals_sign does: its sign, or the exact one.
  int n = 0;
  if (const auto f = decide(v.c[3], permanent_n, kFilterRoundings3); f.decided) {
    ++counters.filtered;
    n = f.sign;
  } else {
    ++counters.exact;
    n = detail::exact_normals_sign(p1, p2, p3);
  }
  if (n == 0) return std::nullopt;
  for (double& c : v.c) c *= n;
  return v;
}

FilterBox filter_box(const VertexCofactors* vertices, std::size_t count) {
  constexpr double u = 0x1p-53;
  FilterBox box;
  double lo[3], hi[3];
  for (int j = 0; j < 3; ++j) {
    lo[j] = std::numeric_limits<double>::infinity();
    hi[j] = -lo[j];
  }
  for (std::size_t i = 0; i < count; ++i) {
    const VertexCofactors& v = vertices[i];
    const double w = v.c[3];
    if (!(w > 2 * v.error_d)) return box;  // unbounded
    const double below = w - v.error_d;
    for (int j = 0; j < 3; ++j) {
      const double x = v.c[j] / w;
      const double delta = (v.error_abc + std::abs(x) * (1 + 2 * u) * v.error_d) / below + 2 * u * std::abs(x);
      const double widened = (delta + 4 * u * std::abs(x)) * (1 + 0x1p-40);
      lo[j] = std::min(lo[j], x - widened);
      hi[j] = std::max(hi[j], x + widened);
    }
  }
  for (int j = 0; j < 3; ++j) {
    box.centre[j] = 0.5 * (lo[j] + hi[j]);
    box.half[j] = std::max(hi[j] - box.centre[j], box.centre[j] - lo[j]) * (1 + 0x1p-48);
    if (!std::isfinite(box.centre[j]) || !std::isfinite(box.half[j])) return box;
  }
  box.bounded = count > 0;
  return box;
}

FilterBox united(const FilterBox& a, const FilterBox& b) {
  constexpr double u = 0x1p-53;
  FilterBox box;
  if (!a.bounded || !b.bounded) return box;
  for (int j = 0; j < 3; ++j) {
    const double lo = std::min(a.centre[j] - a.half[j], b.centre[j] - b.half[j]);
    const double hi = std::max(a.centre[j] + a.half[j], b.centre[j] + b.half[j]);
    const double magnitude = std::max(std::abs(a.centre[j]) + a.half[j], std::abs(b.centre[j]) + b.half[j]);
    box.centre[j] = 0.5 * (lo + hi);
    box.half[j] = (std::max(hi - box.centre[j], box.centre[j] - lo) + 8 * u * magnitude) * (1 + 0x1p-48);
    if (!std::isfinite(box.centre[j]) || !std::isfinite(box.half[j])) return box;
  }
  box.bounded = true;
  return box;
}

int box_side(const FilterBox& b, const PlaneApprox& p) {
  const detail::MaybeSign s = detail::filtered_box_side(b, p);
  return s.decided ? s.sign : 0;
}

std::optional<Vec3> vertex_position(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const Grid& grid) {
  const Matrix<Exact, 3> n = normals<Exact>(p1, p2, p3, to_exact);
  const Exact det = det3<Exact, false>(n);
  if (det.sign() == 0) return std::nullopt;
  // N x = -(d1, d2, d3): coordinate j is -det(N with column j replaced by the offsets) / det N.
  const auto solve = [&](int j) {
    Matrix<Exact, 3> m = n;
    const GridPlane* p[] = {&p1, &p2, &p3};
    for (int i = 0; i < 3; ++i) m[i][j] = Exact(p[i]->d);
    return -det3<Exact, false>(m).to_double() / det.to_double();
  };
  return grid.origin() + Vec3{solve(0), solve(1), solve(2)} * grid.step();
}

int side_of_vertex(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4,
                   PredicateCounters& counters) {
  const int n = normals_sign(p1, p2, p3, counters);
  if (n == 0) return 0;
  return n * planes_sign(p1, p2, p3, p4, counters);
}

}  // namespace bsp
