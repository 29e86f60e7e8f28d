#include "geometry/exact_predicates.h"

#include <algorithm>
#include <array>
#include <cmath>

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

// Each conversion rounds once, to nearest.
double to_double(Int128 v) { return static_cast<double>(v); }
double to_magnitude(Int128 v) { return std::abs(static_cast<double>(v)); }
Exact to_exact(Int128 v) { return Exact(v); }

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
  return det3<Exact, false>(normals<Exact>(p1, p2, p3, to_exact)).sign();
}

int exact_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4) {
  return det4<Exact, false>(planes<Exact>(p1, p2, p3, p4, to_exact)).sign();
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
  const int n = normals_sign(p1, p2, p3, counters);
  if (n == 0) return std::nullopt;
  const Matrix<double, 4> m = planes<double>(p1, p2, p3, p1, to_double);      // row 3 unused
  const Matrix<double, 4> mag = planes<double>(p1, p2, p3, p1, to_magnitude);
  // The minor of rows 0..2 without column `skip`, in the column order the expansion above uses.
  const auto minor = [](const Matrix<double, 4>& a, int skip) {
    Matrix<double, 3> out{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0, k = 0; j < 4; ++j)
        if (j != skip) out[i][k++] = a[i][j];
    return out;
  };
  VertexCofactors v;
  for (int j = 0; j < 4; ++j) {
    const double sign = ((3 + j) % 2 == 0 ? 1.0 : -1.0) * n;  // (-1)^(3 + j) * sign(det N)
    v.c[j] = sign * det3<double, false>(minor(m, j));
    const double error = (kFilterRoundings3 + 1) * 0x1p-53 * det3<double, true>(minor(mag, j));
    (j == 3 ? v.error_d : v.error_abc) = std::max(j == 3 ? v.error_d : v.error_abc, error);
  }
  return v;
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
