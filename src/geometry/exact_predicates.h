#pragma once
// The exact kernel's predicates on grid planes (geometry/grid_plane.h): signs of determinants,
// decided exactly. A vertex is never stored: it is the point where three planes meet, and the one
// question asked of it is its side of a fourth plane [Sugihara1989] [BernsteinFussell2009].
//
// Notation: plane i is (n_i, d_i) with normal n_i = (a_i, b_i, c_i). N is the 3x3 matrix of rows
// n_1, n_2, n_3 and M the 4x4 matrix of rows (n_i, d_i), i = 1..4.
//  - The three planes meet in one point X iff det N != 0, and N X = -(d_1, d_2, d_3).
//  - By the Schur complement, det M = det N * (n_4 . X + d_4): plane 4's value at X has the sign of
//    det M * det N. So side_of_vertex needs two determinant signs.
//
// Stage 1, the filter. Each determinant is expanded along its first column, each sum taken left to
// right, in doubles. A term of det_k is a product of k entries, each rounded once on conversion
// (the entries exceed 53 bits), with k - 1 multiplications and at most 1 + 2 + ... + (k - 1)
// additions on its way, so [Higham2002 §3.1] the computed value differs from det by at most
// gamma_m * perm(|A|), gamma_m = m u / (1 - m u), u = 2^-53, with m = 8 for k = 3 and m = 13 for
// k = 4 (kFilterRoundings). The permanent computed the same way from |entries| is within the same
// factor of the true one, so |det~ - det| <= gamma_m / (1 - gamma_m) * perm~ <= (m + 1) u (1 - u)
// perm~, and the threshold fl((m + 1) u * perm~) is at least that. When |det~| exceeds it, det~ has
// det's sign. When perm~ is 0 every term has a zero entry (integers never round to 0), so det = 0.
// Nothing underflows (nonzero terms are at least 1) or overflows (below 2^380). Contraction into
// fused multiply-adds only removes roundings, so the bound holds for any -ffp-contract setting.
//
// Stage 2, the fallback: det M expanded along the offsets, det M = sum_i (-1)^(i+3) d_i det N_i
// (N_i the normals without row i), each partial result in the narrowest WideInt that holds it
// (kNormalBits = 83, kOffsetBits = 125): the 2x2 minors of normals < 2 * 2^166 = 2^167 (3 limbs),
// det N_i < 3 * 2^83 * 2^167 < 2^252 (4 limbs), d_i det N_i < 2^377 and their sum < 2^379 (6
// limbs); det N alone is the same det N_i.
#include <cmath>
#include <cstdint>
#include <optional>

#include "geometry/grid_plane.h"

namespace bsp {

// How the predicates were decided (best: all by the filter).
struct PredicateCounters {
  std::uint64_t filtered = 0;  // decided by the floating-point filter
  std::uint64_t exact = 0;     // the filter could not decide; decided in wide integers
  void add(const PredicateCounters& o) {
    filtered += o.filtered;
    exact += o.exact;
  }
};

// Rounding errors on a term's path in a determinant of order 3 and 4 (see above).
inline constexpr int kFilterRoundings3 = 8;
inline constexpr int kFilterRoundings4 = 13;

// Sign of det N: nonzero iff the three planes meet in exactly one point.
int normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, PredicateCounters& counters);
// Sign of det M.
int planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4,
                PredicateCounters& counters);
// The side of p4 on which the point where p1, p2 and p3 meet lies: +1 front, -1 behind, 0 on it.
// The three must meet in one point (normals_sign != 0); for three that do not, 0.
int side_of_vertex(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4,
                   PredicateCounters& counters);

// Where p1, p2 and p3 meet, in scene coordinates, by Cramer's rule in WideInt<7> (the numerators,
// determinants with the offsets as a column, stay below 2^295), then converted to doubles and
// divided (a few roundings, each of 2^-53 relative): for output only (OBJ files, the Embree scene, drawing), never for a decision. nullopt when the
// three do not meet in one point.
std::optional<Vec3> vertex_position(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const Grid& grid);

// A vertex prepared for many side tests, the filter in the form of indirect predicates
// [Attene2020]: expanding det M along the fourth plane's row gives det M = a C_0 + b C_1 + c C_2 +
// d C_3, where the cofactors C_j depend only on the three planes that make the vertex (C_3 = det N).
// They are computed once, in doubles, each with the filter's bound on its error (9 u perm~, as
// above) and multiplied by sign(det N) (decided exactly, once), so that the sign of the sum is the
// vertex's side of any fourth plane. The test of one plane then costs four products.
//
// Bound of the test: with p~_j the plane's coefficients rounded to doubles (relative error u) and
// e_j the cofactors' bounds, the computed sum differs from det M * sign(det N) by at most
// (gamma_4 + u / (1 - u)) S + (1 + u / (1 - u)) E, where S = sum |p~_j C~_j| and E = sum |p~_j| e_j
// [Higham2002 §3.1]. The test's threshold, 2^-50 S~ + (1 + 2^-40) E~ with S~ and E~ computed in
// doubles (each within 6 u of the true sum), exceeds that: 8 u > 5.1 u and 2^-40 > 9 u.
struct VertexCofactors {
  double c[4] = {0, 0, 0, 0};  // sign(det N) * (C_0, C_1, C_2, C_3)
  double error_abc = 0;        // bound on the error of c[0], c[1] and c[2]
  double error_d = 0;          // bound on the error of c[3]
};
// The coefficients of a plane rounded to doubles (each once, to nearest), for filtered tests.
struct PlaneApprox {
  double a = 0, b = 0, c = 0, d = 0;
};
PlaneApprox approximate(const GridPlane& p);
// The cofactors of the point where p1, p2 and p3 meet; nullopt when they do not meet in one point.
std::optional<VertexCofactors> vertex_cofactors(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3,
                                                PredicateCounters& counters);
// The same with the planes' approximations given (approximate(p_i)), for callers that keep them:
// converting a 128-bit coefficient is a library call.
std::optional<VertexCofactors> vertex_cofactors(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3,
                                                const PlaneApprox& a1, const PlaneApprox& a2, const PlaneApprox& a3,
                                                PredicateCounters& counters);

// A box in grid coordinates containing the exact vertices of a polygon, from their cofactors, so
// that one test can decide a whole polygon against a plane (as the float kernel's bounding sphere
// does, with proven margins). Vertex X = C / C_3 is rounded to x~ = fl(C~ / C~_3), which is within
// delta = (e_abc + |x~| (1 + 2u) e_d) / (C~_3 - e_d) + 2u |x~| of X per axis when C~_3 > e_d
// (from |C - C~| <= e_abc and |C_3 - C~_3| <= e_d); the box takes each x~ -+ (delta + 4u|x~|)
// (1 + 2^-40), whose rounding then keeps X inside, and is stored as centre and half-widths widened
// by 2^-48 so that centre +- half still covers it. A vertex with C~_3 <= 2 e_d leaves the box
// unbounded (it decides nothing).
//
// The test of a plane: the plane's value over the box lies within v -+ r, v = a . centre + d and
// r = |a| . half; computed in doubles, v is within 2^-50 S of the true value (S = sum of the
// absolute terms, as above) and r is at most 2^-50 r too small. The box is decided when |v~| exceeds
// r~ (1 + 2^-45) + 2^-45 S~, a margin that also covers the rounding of that expression.
struct FilterBox {
  double centre[3] = {0, 0, 0};
  double half[3] = {0, 0, 0};
  bool bounded = false;
};
FilterBox filter_box(const VertexCofactors* vertices, std::size_t count);
// A box holding both boxes: their bounds as lo and hi, widened by the rounding of computing them
// (8u of each coordinate's magnitude) before filter_box's own 2^-48. Unbounded when either is.
FilterBox united(const FilterBox& a, const FilterBox& b);
// Where a box lies against a plane (filtered_box_side): +1 wholly in front, -1 wholly behind, 0
// undecided.
int box_side(const FilterBox& b, const PlaneApprox& p);

// The stages on their own, for tests: a filter result is `decided` only when its bound allows.
namespace detail {
struct MaybeSign {
  bool decided = false;
  int sign = 0;
};
MaybeSign filtered_normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3);
MaybeSign filtered_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4);
int exact_normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3);
int exact_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4);
// The side of the vertex of `v` with respect to the plane `p` when the bound above decides it.
inline MaybeSign filtered_side(const VertexCofactors& v, const PlaneApprox& p) {
  const double t0 = p.a * v.c[0], t1 = p.b * v.c[1], t2 = p.c * v.c[2], t3 = p.d * v.c[3];
  const double sum = ((t0 + t1) + t2) + t3;
  const double s = ((std::abs(t0) + std::abs(t1)) + std::abs(t2)) + std::abs(t3);
  const double e = (std::abs(p.a) + std::abs(p.b) + std::abs(p.c)) * v.error_abc + std::abs(p.d) * v.error_d;
  const double threshold = 0x1p-50 * s + (1 + 0x1p-40) * e;
  if (sum > threshold) return {true, 1};
  if (sum < -threshold) return {true, -1};
  return {false, 0};
}
// +1 when every point of the box is strictly in front of the plane, -1 strictly behind, else
// undecided.
inline MaybeSign filtered_box_side(const FilterBox& b, const PlaneApprox& p) {
  if (!b.bounded) return {false, 0};
  const double t0 = p.a * b.centre[0], t1 = p.b * b.centre[1], t2 = p.c * b.centre[2];
  const double v = ((t0 + t1) + t2) + p.d;
  const double s = ((std::abs(t0) + std::abs(t1)) + std::abs(t2)) + std::abs(p.d);
  const double r = (std::abs(p.a) * b.half[0] + std::abs(p.b) * b.half[1]) + std::abs(p.c) * b.half[2];
  const double margin = r * (1 + 0x1p-45) + 0x1p-45 * s;
  if (v > margin) return {true, 1};
  if (v < -margin) return {true, -1};
  return {false, 0};
}
}  // namespace detail

}  // namespace bsp
