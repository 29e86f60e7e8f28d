// The exact kernel's grid, planes and predicates against GMP's integers: snapping stays within its
// bound at the grid's limits, coefficients stay within theirs, and every sign the predicates give
// (the filter's and the fallback's) is GMP's, on random planes at the limits and on degenerate ones
// (four planes through one point, nearly parallel planes, grazing planes).
#include <gmp.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "common/rng.h"
#include "geometry/exact_predicates.h"
#include "geometry/grid.h"
#include "geometry/grid_plane.h"
#include "geometry/plane_polygon.h"
#include "geometry/snap.h"
#include "catalog.h"
#include "scene/scene.h"
#include "geometry/wide_int.h"

using namespace bsp;

namespace {

// An mpz_t that frees itself.
struct Mpz {
  mpz_t v;
  Mpz() { mpz_init(v); }
  explicit Mpz(Int128 x) : Mpz() {
    const bool negative = x < 0;
    const auto m = static_cast<unsigned __int128>(negative ? -x : x);
    mpz_set_ui(v, static_cast<unsigned long>(m >> 64));
    mpz_mul_2exp(v, v, 64);
    mpz_add_ui(v, v, static_cast<unsigned long>(static_cast<std::uint64_t>(m)));
    if (negative) mpz_neg(v, v);
  }
  ~Mpz() { mpz_clear(v); }
  Mpz(const Mpz&) = delete;
  Mpz& operator=(const Mpz&) = delete;
};

// GMP's determinant of a square matrix of at most 4 rows, by Laplace expansion along the first
// column, each minor (a set of rows over the last columns) computed once.
class GmpMatrix {
 public:
  explicit GmpMatrix(const std::vector<std::vector<Int128>>& rows) : n_(static_cast<int>(rows.size())) {
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) {
        Mpz x(rows[i][j]);
        mpz_init_set(m_[i][j], x.v);
      }
    for (auto& v : minor_) mpz_init(v);
  }
  ~GmpMatrix() {
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) mpz_clear(m_[i][j]);
    for (auto& v : minor_) mpz_clear(v);
  }
  GmpMatrix(const GmpMatrix&) = delete;
  GmpMatrix& operator=(const GmpMatrix&) = delete;

  int sign() { return mpz_sgn(det((1u << n_) - 1)); }

 private:
  // The minor of the rows in `mask` over the last popcount(mask) columns.
  const mpz_t& det(unsigned mask) {
    mpz_t& out = minor_[mask];
    if (done_[mask]) return out;
    done_[mask] = true;
    const int column = n_ - __builtin_popcount(mask);
    mpz_set_ui(out, 0);
    Mpz term;
    int parity = 0;
    for (int r = 0; r < n_; ++r) {
      if (!(mask & (1u << r))) continue;
      const unsigned rest = mask & ~(1u << r);
      if (rest == 0) mpz_set(term.v, m_[r][column]);
      else mpz_mul(term.v, m_[r][column], det(rest));
      if (parity++ % 2 == 0) mpz_add(out, out, term.v);
      else mpz_sub(out, out, term.v);
    }
    return out;
  }

  int n_;
  mpz_t m_[4][4];
  mpz_t minor_[16];
  bool done_[16] = {};
};

int gmp_sign(const std::vector<std::vector<Int128>>& m) { return GmpMatrix(m).sign(); }

int gmp_normals_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3) {
  return gmp_sign({{p1.a, p1.b, p1.c}, {p2.a, p2.b, p2.c}, {p3.a, p3.b, p3.c}});
}

int gmp_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4) {
  return gmp_sign({{p1.a, p1.b, p1.c, p1.d}, {p2.a, p2.b, p2.c, p2.d}, {p3.a, p3.b, p3.c, p3.d}, {p4.a, p4.b, p4.c, p4.d}});
}

constexpr std::int64_t kGridMax = (std::int64_t{1} << kGridBits) - 1;

std::int64_t coordinate(Rng& rng, std::int64_t bound) {
  return static_cast<std::int64_t>(rng.below(2 * static_cast<std::uint64_t>(bound) + 1)) - bound;
}

GridPoint random_point(Rng& rng, std::int64_t bound = kGridMax) {
  return {coordinate(rng, bound), coordinate(rng, bound), coordinate(rng, bound)};
}

GridPoint offset(const GridPoint& p, std::int64_t dx, std::int64_t dy, std::int64_t dz) {
  return {p.x + dx, p.y + dy, p.z + dz};
}

GridPoint clamp(const GridPoint& p) {
  const auto c = [](std::int64_t v) { return std::max(-kGridMax, std::min(kGridMax, v)); };
  return {c(p.x), c(p.y), c(p.z)};
}

// A plane through three random points of the grid's extreme range, never degenerate.
GridPlane random_plane(Rng& rng, std::int64_t bound = kGridMax) {
  for (;;)
    if (auto p = plane_through(random_point(rng, bound), random_point(rng, bound), random_point(rng, bound))) return *p;
}

// A random plane through x (grid point), through x and two random grid points.
GridPlane plane_through_point(Rng& rng, const GridPoint& x) {
  for (;;)
    if (auto p = plane_through(x, random_point(rng), random_point(rng))) return *p;
}

// The sign of det M in doubles with no bound: what a kernel without the filter would answer.
int naive_planes_sign(const GridPlane& p1, const GridPlane& p2, const GridPlane& p3, const GridPlane& p4) {
  const GridPlane* p[] = {&p1, &p2, &p3, &p4};
  double m[4][4];
  for (int i = 0; i < 4; ++i) {
    m[i][0] = static_cast<double>(p[i]->a);
    m[i][1] = static_cast<double>(p[i]->b);
    m[i][2] = static_cast<double>(p[i]->c);
    m[i][3] = static_cast<double>(p[i]->d);
  }
  double det = 0;
  for (int i = 0; i < 4; ++i) {
    double r[3][3];
    for (int k = 0, row = 0; k < 4; ++k)
      if (k != i) {
        for (int j = 0; j < 3; ++j) r[row][j] = m[k][j + 1];
        ++row;
      }
    const double minor = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[1][0] * (r[0][1] * r[2][2] - r[0][2] * r[2][1]) +
                         r[2][0] * (r[0][1] * r[1][2] - r[0][2] * r[1][1]);
    det += (i % 2 ? -1 : 1) * m[i][0] * minor;
  }
  return (det > 0) - (det < 0);
}

struct Quad {
  GridPlane p[4];
};

// The degenerate families the filter cannot decide alone, each generated at the grid's limits.
std::vector<Quad> adversarial_cases(Rng& rng, std::size_t per_family) {
  std::vector<Quad> out;
  for (std::size_t i = 0; i < per_family; ++i) {  // four planes through one point: det M = 0
    const GridPoint x = random_point(rng);
    out.push_back({{plane_through_point(rng, x), plane_through_point(rng, x), plane_through_point(rng, x),
                    plane_through_point(rng, x)}});
  }
  for (std::size_t i = 0; i < per_family; ++i) {  // the fourth plane misses the vertex by one step
    const GridPoint x = random_point(rng, kGridMax - 1);
    const GridPlane p1 = plane_through_point(rng, x), p2 = plane_through_point(rng, x), p3 = plane_through_point(rng, x);
    const GridPoint near = offset(x, coordinate(rng, 1), coordinate(rng, 1), coordinate(rng, 1));
    out.push_back({{p1, p2, p3, plane_through_point(rng, near)}});
  }
  for (std::size_t i = 0; i < per_family; ++i) {  // nearly parallel: planes through nearly the same three points
    const GridPoint a = random_point(rng, kGridMax - 2), b = random_point(rng, kGridMax - 2), c = random_point(rng, kGridMax - 2);
    Quad q;
    for (auto& p : q.p) {
      const auto moved = [&](const GridPoint& g) {
        return clamp(offset(g, coordinate(rng, 2), coordinate(rng, 2), coordinate(rng, 2)));
      };
      for (;;)
        if (auto plane = plane_through(moved(a), moved(b), moved(c))) {
          p = *plane;
          break;
        }
    }
    out.push_back(q);
  }
  for (std::size_t i = 0; i < per_family; ++i) {  // a grazing split: the fourth plane shares two planes' line
    const GridPoint x = random_point(rng), y = random_point(rng);
    Quad q;
    for (auto& p : q.p)
      for (;;)
        if (auto plane = plane_through(x, y, random_point(rng))) {
          p = *plane;
          break;
        }
    out.push_back(q);
  }
  return out;
}

}  // namespace

TEST(WideInt, SumsAndProductsAreGmps) {
  Rng rng(11);
  for (int i = 0; i < 20000; ++i) {
    const auto wide = [&] {
      const auto hi = static_cast<Int128>(static_cast<std::int64_t>(rng.next()) >> rng.below(64));
      return (hi << 62) + static_cast<Int128>(rng.next() >> 2);
    };
    const Int128 a = wide(), b = wide(), c = wide();
    // a * b * c needs up to 378 bits; (a * b - c * c) * a and its sum with a stay inside 448.
    const WideInt<7> w = (WideInt<7>(a) * WideInt<7>(b) - WideInt<7>(c) * WideInt<7>(c)) * WideInt<7>(a) + WideInt<7>(a);
    Mpz ma(a), mb(b), mc(c), t, u;
    mpz_mul(t.v, ma.v, mb.v);
    mpz_mul(u.v, mc.v, mc.v);
    mpz_sub(t.v, t.v, u.v);
    mpz_mul(t.v, t.v, ma.v);
    mpz_add(t.v, t.v, ma.v);
    ASSERT_EQ(w.sign(), mpz_sgn(t.v)) << i;
    // The low 64 bits agree too (two's complement of the same integer).
    ASSERT_EQ(w.limb(0), static_cast<std::uint64_t>(mpz_get_ui(t.v) * (mpz_sgn(t.v) < 0 ? -1ul : 1ul))) << i;
  }
}

TEST(Grid, SnappingMovesNoVertexFartherThanItsBound) {
  Rng rng(3);
  // Boxes far from the origin, tiny, flat and huge.
  const Box boxes[] = {{{-1, -1, -1}, {1, 1, 1}},
                       {{1e6, 1e6, 1e6}, {1e6 + 1e-3, 1e6 + 2e-3, 1e6 + 1e-3}},
                       {{0, 0, 5}, {10, 20, 5}},
                       {{-3e12, 7, -1}, {4e12, 9, 1}}};
  for (const Box& box : boxes) {
    const Grid grid = Grid::for_box(box);
    const double bound = kSnapRelative * box.diagonal();
    EXPECT_LE(grid.step() * std::sqrt(3.0) / 2, bound);
    EXPECT_GT(grid.step() * std::sqrt(3.0), bound);  // the largest power of two within the bound
    SnapStats stats;
    for (int i = 0; i < 10000; ++i) {
      Vec3 p{rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y), rng.uniform(box.lo.z, box.hi.z)};
      if (i < 8) p = {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z};
      const auto q = grid.snap(p);
      ASSERT_TRUE(q.has_value());
      for (std::int64_t c : {q->x, q->y, q->z}) ASSERT_LE(std::abs(c), kGridMax);
      stats.add(length(grid.point(*q) - p));
    }
    EXPECT_LE(stats.max_displacement, bound * (1 + 1e-6));
    // Random points of the unit box move; where doubles are coarser than the grid (the box at
    // 10^6 of size 10^-3: its points are multiples of 2^-33, the step 2^-49) nothing moves.
    if (&box == &boxes[0]) {
      EXPECT_GT(stats.moved, 9000u);
    }
    if (&box == &boxes[1]) {
      EXPECT_EQ(stats.moved, 0u);
    }
  }
}

TEST(Grid, RefusesPointsOutsideItsRange) {
  const Grid grid = Grid::for_box({{-1, -1, -1}, {1, 1, 1}});
  EXPECT_FALSE(grid.snap({1e6, 0, 0}).has_value());
  EXPECT_FALSE(grid.snap({std::nan(""), 0, 0}).has_value());
  EXPECT_FALSE(grid.snap({0, INFINITY, 0}).has_value());
}

TEST(GridPlane, CoefficientsStayWithinTheirBoundsAtTheGridsLimits) {
  // The extreme planes: through corners of the grid's cube.
  const std::int64_t m = kGridMax;
  const auto plane = plane_through({-m, -m, -m}, {m, -m, m}, {-m, m, m});
  ASSERT_TRUE(plane.has_value());
  Rng rng(5);
  std::vector<GridPlane> planes{*plane};
  for (int i = 0; i < 100000; ++i) planes.push_back(random_plane(rng));
  const Int128 normal_bound = Int128{1} << kNormalBits, offset_bound = Int128{1} << kOffsetBits;
  Int128 largest_normal = 0;
  for (const GridPlane& p : planes) {
    for (Int128 c : {p.a, p.b, p.c}) {
      ASSERT_LT(c < 0 ? -c : c, normal_bound);
      largest_normal = std::max(largest_normal, c < 0 ? -c : c);
    }
    ASSERT_LT(p.d < 0 ? -p.d : p.d, offset_bound);
  }
  // The bound is tight to within a factor of 4: the corners reach past 2^81.
  EXPECT_GT(largest_normal, Int128{1} << (kNormalBits - 2));
}

TEST(GridPlane, AnEdgePlaneCutsItsFacesPlaneInTheEdge) {
  Rng rng(8);
  for (int i = 0; i < 10000; ++i) {
    const GridPoint p = random_point(rng), q = random_point(rng), r = random_point(rng);
    const auto support = plane_through(p, q, r);
    if (!support) continue;
    const auto edge = edge_plane(p, q, *support, r);
    ASSERT_TRUE(edge.has_value());
    EXPECT_EQ(edge->side(p), 0);
    EXPECT_EQ(edge->side(q), 0);
    EXPECT_EQ(edge->side(r), 1);
    // The edge plane is transverse to the support: the two meet in a line, not a plane.
    const GridPlane& s = *support;
    const GridPlane& e = *edge;
    EXPECT_FALSE(s.a * e.b == s.b * e.a && s.b * e.c == s.c * e.b && s.a * e.c == s.c * e.a);
  }
}

// Three planes through a grid point x: the vertex they define is x, so its side of a fourth plane
// is that plane's value at x, computed directly in 128 bits.
TEST(ExactPredicates, TheVertexOfThreePlanesIsTheirCommonPoint) {
  Rng rng(21);
  PredicateCounters counters;
  int on = 0;
  for (int i = 0; i < 20000; ++i) {
    const GridPoint x = random_point(rng, kGridMax - 1);
    const GridPlane p1 = plane_through_point(rng, x), p2 = plane_through_point(rng, x), p3 = plane_through_point(rng, x);
    if (normals_sign(p1, p2, p3, counters) == 0) continue;
    const GridPoint near = offset(x, coordinate(rng, 1), coordinate(rng, 1), coordinate(rng, 1));
    const GridPlane p4 = plane_through_point(rng, near);
    ASSERT_EQ(side_of_vertex(p1, p2, p3, p4, counters), p4.side(x)) << i;
    on += p4.side(x) == 0;
  }
  EXPECT_GT(on, 500);  // a fourth plane through x (near == x) is one case in 27: about 740
  EXPECT_GT(counters.exact, 0u);
}

// The predicates against GMP on a million cases: random planes at the grid's limits and the four
// degenerate families. Both stages are checked: every sign the filter decides, and every case
// again through the exact fallback alone.
TEST(ExactPredicates, AgreeWithGmpOnAMillionRandomAndDegenerateCases) {
  Rng rng(1);
  std::vector<Quad> cases = adversarial_cases(rng, 100000);
  while (cases.size() < 1000000) cases.push_back({{random_plane(rng), random_plane(rng), random_plane(rng), random_plane(rng)}});
  std::uint64_t disagreements = 0, filter_decided = 0, side_decided = 0, naive_wrong = 0, zero_det = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const GridPlane* p = cases[i].p;
    const int truth4 = gmp_planes_sign(p[0], p[1], p[2], p[3]);
    const int truth3 = gmp_normals_sign(p[0], p[1], p[2]);
    zero_det += truth4 == 0;
    if (const auto f = detail::filtered_planes_sign(p[0], p[1], p[2], p[3]); f.decided) {
      ++filter_decided;
      disagreements += f.sign != truth4;
    }
    if (const auto f = detail::filtered_normals_sign(p[0], p[1], p[2]); f.decided) disagreements += f.sign != truth3;
    disagreements += detail::exact_planes_sign(p[0], p[1], p[2], p[3]) != truth4;
    disagreements += detail::exact_normals_sign(p[0], p[1], p[2]) != truth3;
    PredicateCounters counters;
    disagreements += planes_sign(p[0], p[1], p[2], p[3], counters) != truth4;
    // The vertex's cached cofactors against the fourth plane: the sign of det M * det N.
    if (truth3 != 0) {
      const auto v = vertex_cofactors(p[0], p[1], p[2], counters);
      if (const auto f = detail::filtered_side(*v, approximate(p[3])); f.decided) {
        ++side_decided;
        disagreements += f.sign != truth3 * truth4;
      }
    }
    naive_wrong += naive_planes_sign(p[0], p[1], p[2], p[3]) != truth4;
  }
  EXPECT_EQ(disagreements, 0u);
  // Four planes through a point and the grazing family have det M = 0 (the filter passes them on
  // unless a zero entry makes the permanent 0); random planes it decides alone. That the filter's
  // threshold is large enough rests on the proof in exact_predicates.h: rounding errors this large
  // are rare, so a threshold a few times too small could still pass here.
  EXPECT_GE(zero_det, 200000u);
  EXPECT_GE(filter_decided, 600000u);
  EXPECT_GE(side_decided, 600000u);
  // Without the filter's bound, doubles get tens of thousands of these signs wrong.
  EXPECT_GT(naive_wrong, 10000u);
}

namespace {

// A convex polygon of `corners` grid points on a random tilted plane: points of a circle of radius
// r in (x, y), lifted to z = z0 + s x + t y with small integer slopes (an affine map keeps
// convexity and coplanarity exactly).
std::vector<GridPoint> convex_points(Rng& rng, int corners) {
  const std::int64_t r = 1 + static_cast<std::int64_t>(rng.below(std::uint64_t{1} << 36));
  const std::int64_t cx = coordinate(rng, std::int64_t{1} << 37), cy = coordinate(rng, std::int64_t{1} << 37);
  const std::int64_t s = coordinate(rng, 3), t = coordinate(rng, 3), z0 = coordinate(rng, std::int64_t{1} << 36);
  std::vector<GridPoint> out;
  for (int i = 0; i < corners; ++i) {
    const double a = 2 * M_PI * (i + 0.3 * rng.uniform()) / corners;
    const std::int64_t x = cx + std::llround(r * std::cos(a)), y = cy + std::llround(r * std::sin(a));
    out.push_back({x, y, z0 + s * (x - cx) + t * (y - cy)});
  }
  return out;
}

// Newell's normal of the vertex loop, relative to its first vertex (so that only the positions' own
// rounding remains): along the side it is seen counter-clockwise from, twice the area long.
Vec3 winding(const std::vector<Vec3>& p) {
  Vec3 n{};
  for (std::size_t i = 1; i + 1 < p.size(); ++i) n += cross(p[i] - p[0], p[i + 1] - p[0]);
  return n;
}

double polygon_area(const std::vector<Vec3>& p) { return length(winding(p)) / 2; }

double perimeter(const std::vector<Vec3>& p) {
  double sum = 0;
  for (std::size_t i = 0; i < p.size(); ++i) sum += length(p[(i + 1) % p.size()] - p[i]);
  return sum;
}

}  // namespace

TEST(PlanePolygon, RefusesDegenerateAndNonConvexInput) {
  const std::vector<GridPoint> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  EXPECT_FALSE(plane_polygon(line, 0).has_value());
  const std::vector<GridPoint> bent{{0, 0, 0}, {4, 0, 0}, {4, 4, 1}, {0, 4, 0}};  // not planar
  EXPECT_FALSE(plane_polygon(bent, 0).has_value());
  const std::vector<GridPoint> dart{{0, 0, 0}, {4, 0, 0}, {1, 1, 0}, {0, 4, 0}};  // not convex
  EXPECT_FALSE(plane_polygon(dart, 0).has_value());
  // A repeated point and a point in the middle of an edge bound nothing and are left out.
  const std::vector<GridPoint> square{{0, 0, 0}, {2, 0, 0}, {4, 0, 0}, {4, 4, 0}, {4, 4, 0}, {0, 4, 0}};
  const auto poly = plane_polygon(square, 7);
  ASSERT_TRUE(poly.has_value());
  EXPECT_EQ(poly->size(), 4u);
  EXPECT_EQ(poly->source, 7u);
  PredicateCounters counters;
  EXPECT_TRUE(is_valid(*poly, counters));
}

TEST(PlanePolygon, VerticesAreTheGivenPoints) {
  Rng rng(31);
  const Grid grid = Grid::for_box({{-1, -1, -1}, {1, 1, 1}});
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::vector<GridPoint> points = convex_points(rng, 3 + static_cast<int>(rng.below(6)));
    const auto poly = plane_polygon(points, 0);
    if (!poly || poly->size() != points.size()) continue;
    ++checked;
    const std::vector<Vec3> v = vertex_positions(*poly, grid);
    ASSERT_EQ(v.size(), points.size());
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Vec3 expected = grid.point(points[(k + 1) % points.size()]);
      // The quotient of two rounded determinants, then the origin added: a few ulps of 1.
      ASSERT_LE(length(v[k] - expected), 1e-15) << i;
    }
  }
  EXPECT_GT(checked, 1500);
}

namespace {

// The cached filters of the exact fragments against the exact sides: a box that decides puts every
// vertex strictly on its side, and a vertex's cofactor filter that decides agrees. Returns 1 when
// the box decided.
int check_box_and_vertex_filters(const PlanePolygon& poly, const GridPlane& plane, PredicateCounters& counters) {
  std::vector<VertexCofactors> cofactors;
  const PlaneApprox approx = approximate(plane);
  const std::vector<int> sides = vertex_sides(poly, plane, counters);
  for (std::size_t i = 0; i < poly.size(); ++i) {
    cofactors.push_back(*vertex_cofactors(poly.support, poly.before(i), poly.after(i), counters));
    const auto f = detail::filtered_side(cofactors.back(), approx);
    EXPECT_TRUE(!f.decided || f.sign == sides[i]);
  }
  const auto whole = detail::filtered_box_side(filter_box(cofactors.data(), cofactors.size()), approx);
  if (!whole.decided) return 0;
  for (int side : sides) EXPECT_EQ(side, whole.sign);
  return 1;
}

}  // namespace

// Splitting by planes through random grid points, through a vertex (grazing) and through two
// vertices (along a diagonal), five levels deep: every part is a valid polygon on its side of
// the plane, the parts share their cut's two vertices exactly and keep the area.
TEST(PlanePolygon, SplitPartsAreValidOnTheirSidesAndKeepTheArea) {
  Rng rng(41);
  const Grid grid = Grid::for_box({{-1, -1, -1}, {1, 1, 1}});
  PredicateCounters counters;
  std::uint64_t spanning = 0, grazing_or_diagonal = 0, splits = 0, box_decided = 0;
  for (int shape = 0; shape < 400; ++shape) {
    const auto start = plane_polygon(convex_points(rng, 3 + static_cast<int>(rng.below(6))), 0);
    if (!start) continue;
    std::vector<PlanePolygon> pieces{*start};
    for (int level = 0; level < 5; ++level) {
      std::vector<PlanePolygon> next;
      for (const PlanePolygon& poly : pieces) {
        // A plane through a point of the polygon's interior (the mean of its vertices on the grid),
        // sometimes through one or two of its vertices.
        const std::vector<Vec3> v = vertex_positions(poly, grid);
        Vec3 mean{};
        for (const Vec3& p : v) mean += p / static_cast<double>(v.size());
        const GridPoint centre = *grid.snap(mean);
        const std::uint64_t kind = rng.below(3);
        const GridPoint a = kind >= 1 ? *grid.snap(v[0]) : random_point(rng);
        const GridPoint b = kind == 2 ? *grid.snap(v[v.size() / 2]) : random_point(rng);
        const auto plane = plane_through(centre, a, b);
        if (!plane) {
          next.push_back(poly);
          continue;
        }
        const PlaneSplit s = split(poly, *plane, counters);
        ++splits;
        box_decided += check_box_and_vertex_filters(poly, *plane, counters);
        box_decided += check_box_and_vertex_filters(poly, random_plane(rng, std::int64_t{1} << 38), counters);
        if (s.side != Side::Spanning) {
          next.push_back(poly);
          continue;
        }
        ++spanning;
        for (int side : vertex_sides(poly, *plane, counters))
          if (side == 0) {
            ++grazing_or_diagonal;  // the cut passes through a vertex
            break;
          }
        ASSERT_TRUE(is_valid(*s.front, counters));
        ASSERT_TRUE(is_valid(*s.back, counters));
        for (int side : vertex_sides(*s.front, *plane, counters)) ASSERT_GE(side, 0);
        for (int side : vertex_sides(*s.back, *plane, counters)) ASSERT_LE(side, 0);
        const std::vector<Vec3> f = vertex_positions(*s.front, grid), bk = vertex_positions(*s.back, grid);
        // Shared vertices, decided exactly: each on the other's three planes.
        int shared = 0;
        for (std::size_t i = 0; i < s.front->size(); ++i)
          for (std::size_t j = 0; j < s.back->size(); ++j) {
            const PlanePolygon &fp = *s.front, &bp = *s.back;
            shared += side_of_vertex(fp.support, fp.before(i), fp.after(i), bp.before(j), counters) == 0 &&
                      side_of_vertex(fp.support, fp.before(i), fp.after(i), bp.after(j), counters) == 0;
          }
        ASSERT_EQ(shared, 2);
        const double whole = polygon_area(v), parts = polygon_area(f) + polygon_area(bk);
        // Positions are rounded once to doubles of magnitude below 1 (an error of 1e-16 each).
        ASSERT_NEAR(parts, whole, 1e-9 * whole + 1e-15 * perimeter(v));
        // Both parts run counter-clockwise seen from the support's front (is_valid decides it
        // exactly); in doubles, within the rounding of positions below 1 (1e-16 each).
        const Vec3 normal = normalize(Vec3{static_cast<double>(poly.support.a), static_cast<double>(poly.support.b),
                                           static_cast<double>(poly.support.c)});
        ASSERT_GT(dot(winding(f), normal), -1e-15 * perimeter(f));
        ASSERT_GT(dot(winding(bk), normal), -1e-15 * perimeter(bk));
        next.push_back(*s.front);
        next.push_back(*s.back);
      }
      pieces = std::move(next);
    }
  }
  EXPECT_GT(spanning, 2000u);
  EXPECT_GT(grazing_or_diagonal, 100u);
  EXPECT_GT(counters.filtered, 0u);
  (void)splits;
  EXPECT_GT(box_decided, 100u);  // the planes through other pieces decide whole pieces
}

TEST(PlanePolygon, BoundsInClockwiseOrderAreInvalid) {
  const std::vector<GridPoint> square{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  PlanePolygon poly = *plane_polygon(square, 0);
  PredicateCounters counters;
  ASSERT_TRUE(is_valid(poly, counters));
  std::reverse(poly.bounds.begin(), poly.bounds.end());
  EXPECT_FALSE(is_valid(poly, counters));
}

// kept_edges (what ExactFragments splits its flat arrays by) lists the bounds part_of keeps, in its
// order, with the kept vertices those bounds meet in.
TEST(PlanePolygon, KeptEdgesAreThePartsBoundsAndVertices) {
  const std::vector<GridPoint> hexagon{{0, 0, 0}, {4, 0, 0}, {6, 3, 0}, {4, 6, 0}, {0, 6, 0}, {-2, 3, 0}};
  const PlanePolygon poly = *plane_polygon(hexagon, 0);
  for (const GridPlane& cut : {*plane_through({1, 0, 0}, {1, 1, 0}, {1, 0, 1}), *plane_through({0, 2, 0}, {5, 4, 0}, {0, 2, 1}),
                               *plane_through({4, 0, 0}, {4, 1, 0}, {4, 0, 1})}) {
    PredicateCounters counters;
    const std::vector<int> sides = vertex_sides(poly, cut, counters);
    for (int keep : {1, -1}) {
      const PolygonPart part = part_of(poly, sides, keep, cut);
      std::vector<std::uint32_t> kept;
      kept_edges(sides, keep, kept);
      ASSERT_EQ(kept.size() + 1, part.poly.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        EXPECT_EQ(part.poly.bounds[i], poly.bounds[kept[i]]);
        if (i + 1 < kept.size()) {
          EXPECT_EQ(part.origin[i], kept[i]);
        }
      }
    }
  }
}

TEST(PlanePolygon, ClassifiesCoplanarFrontAndBack) {
  const std::vector<GridPoint> square{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  const PlanePolygon poly = *plane_polygon(square, 0);
  PredicateCounters counters;
  EXPECT_EQ(split(poly, poly.support, counters).side, Side::Coplanar);
  EXPECT_EQ(split(poly, -poly.support, counters).side, Side::Coplanar);
  const GridPlane x_is_5 = *plane_through({5, 0, 0}, {5, 1, 0}, {5, 0, 1});  // x = 5, a side of the square
  const int square_side = x_is_5.side({0, 0, 0});
  EXPECT_EQ(split(poly, x_is_5, counters).side, square_side > 0 ? Side::Front : Side::Back);
  // Touching along an edge: the edge's vertices are on the plane, the rest on one side.
  const GridPlane x_is_4 = *plane_through({4, 0, 0}, {4, 1, 0}, {4, 0, 1});
  EXPECT_EQ(split(poly, x_is_4, counters).side, square_side > 0 ? Side::Front : Side::Back);
}

TEST(Snap, KeepsTrianglesFansBentQuadsAndCountsWhatCollapsed) {
  const double e = 1e-3;  // the grid step of a box of diagonal ~3.5 is about 2^-41
  const std::vector<Polygon> input{
      {{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}}, 0},                    // a triangle: kept whole
      {{{{0, 0, 1}}, {{1, 0, 1}}, {{1, 1, 1 + e}}, {{0, 1, 1}}}, 1},   // a quad bent by 1e-3: fanned
      {{{{0.5, 0.5, 0.5}}, {{0.5 + 1e-14, 0.5, 0.5}}, {{0.5, 0.5 + 1e-14, 0.5}}}, 2},  // below the grid: a point
      {{{{0, 0, 0}}, {{2, 2, 2}}}, 3},                                  // a segment: not for the 3D kernel
  };
  const SnappedScene s = snap_polygons(input);
  EXPECT_EQ(s.report.polygons, 3u);
  EXPECT_EQ(s.report.not_polygons, 1u);
  EXPECT_EQ(s.report.kept_whole, 1u);
  EXPECT_EQ(s.report.fanned, 1u);
  EXPECT_EQ(s.report.fan_triangles, 2u);
  EXPECT_EQ(s.report.flipped, 0u);
  EXPECT_EQ(s.report.degenerate, 1u);
  EXPECT_GT(s.report.degenerate_area, 0.0);
  ASSERT_EQ(s.polygons.size(), 3u);
  EXPECT_EQ(s.polygons[0].source, 0u);
  EXPECT_EQ(s.polygons[1].source, 1u);
  EXPECT_EQ(s.polygons[2].source, 1u);
  EXPECT_EQ(s.report.vertices.vertices, 10u);
  EXPECT_LE(s.report.vertices.max_displacement, kSnapRelative * std::sqrt(2 * 2 * 3.0) * (1 + 1e-6));
  PredicateCounters counters;
  for (const PlanePolygon& p : s.polygons) EXPECT_TRUE(is_valid(p, counters));
}

// The near-degenerate scene's features are 1e-9 of its diagonal, a thousand grid steps: snapping
// collapses none of them, and every polygon stays a valid plane polygon.
TEST(Snap, NearDegenerateFeaturesSurvive) {
  const Scene scene = make_scene("near-degenerate", {{"n", "1000"}});
  const SnappedScene s = snap_polygons(scene.polygons);
  EXPECT_EQ(s.report.degenerate, 0u);
  EXPECT_EQ(s.report.polygons, scene.polygons.size());
  EXPECT_EQ(s.report.kept_whole + s.report.fanned, scene.polygons.size());
  const double diagonal = bounds(scene).diagonal();
  EXPECT_LE(s.report.vertices.max_displacement, kSnapRelative * diagonal * (1 + 1e-6));
  PredicateCounters counters;
  for (const PlanePolygon& p : s.polygons) ASSERT_TRUE(is_valid(p, counters));
}
