// The exact measuring tools (validate/exact_measure.h): volumes known in closed form come out as
// the exact rationals, a face split into two against undivided neighbours (T-junctions at
// rational points) still closes, and planted faults (a face missing, a face flipped, half of a
// split face missing) are caught with the number of border segments they leave. CGAL's
// corefinement measured exactly agrees with boxes known analytically and, off the axes, with
// boundaries of the results built independently here by clipping plane polygons (their
// vertices rational), and with inclusion-exclusion.
#include <gtest/gtest.h>
#include <gmp.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "geometry/plane_polygon.h"
#include "validate/exact_measure.h"

using namespace bsp;

namespace {

using Mesh = std::vector<std::vector<GridPoint>>;

// The six faces of the box [lo, hi], counter-clockwise seen from outside.
Mesh box(const GridPoint& lo, const GridPoint& hi) {
  const auto c = [&](int i, int j, int k) { return GridPoint{i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z}; };
  return {{c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)}, {c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)},
          {c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)}, {c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)},
          {c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)}, {c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)}};
}

// The four faces of the tetrahedron p0 p1 p2 p3, outward whichever way its points turn.
Mesh tetrahedron(GridPoint p0, GridPoint p1, GridPoint p2, GridPoint p3) {
  const auto sub = [](const GridPoint& a, const GridPoint& b) { return GridPoint{a.x - b.x, a.y - b.y, a.z - b.z}; };
  const GridPoint u = sub(p1, p0), v = sub(p2, p0), w = sub(p3, p0);
  const long long det = u.x * (v.y * w.z - v.z * w.y) - u.y * (v.x * w.z - v.z * w.x) + u.z * (v.x * w.y - v.y * w.x);
  if (det < 0) std::swap(p1, p2);
  return {{p0, p2, p1}, {p0, p1, p3}, {p1, p2, p3}, {p0, p3, p2}};
}

std::vector<PlanePolygon> plane_faces(const Mesh& mesh) {
  std::vector<PlanePolygon> out;
  for (const std::vector<GridPoint>& poly : mesh) {
    const std::optional<PlanePolygon> p = plane_polygon(poly, 0);
    EXPECT_TRUE(p.has_value());
    if (p) out.push_back(*p);
  }
  return out;
}

PlanePolygon flipped(PlanePolygon p) {
  p.support = -p.support;
  std::reverse(p.bounds.begin(), p.bounds.end());
  return p;
}

// The tetrahedron bounded by four planes (fronts outward), each face its support bounded by the
// other three turned inward, in whichever order makes a valid (counter-clockwise) polygon: its
// vertices are wherever the planes meet, rational in general.
std::vector<PlanePolygon> simplex_of_planes(const std::vector<GridPlane>& planes) {
  std::vector<PlanePolygon> out;
  PredicateCounters counters;
  for (std::size_t f = 0; f < 4; ++f) {
    PlanePolygon face{planes[f], {}, 0};
    for (std::size_t g = 0; g < 4; ++g)
      if (g != f) face.bounds.push_back(-planes[g]);
    if (!is_valid(face, counters)) std::swap(face.bounds[1], face.bounds[2]);
    EXPECT_TRUE(is_valid(face, counters));
    out.push_back(face);
  }
  return out;
}

std::vector<GridPlane> supports(const std::vector<PlanePolygon>& faces) {
  std::vector<GridPlane> out;
  for (const PlanePolygon& f : faces) out.push_back(f.support);
  return out;
}

// The part of `poly` inside the convex solid whose outward planes are given (behind all of them).
std::optional<PlanePolygon> clip_inside(PlanePolygon poly, const std::vector<GridPlane>& solid) {
  PredicateCounters counters;
  for (const GridPlane& plane : solid) {
    PlaneSplit s = split(poly, plane, counters);
    EXPECT_NE(s.side, Side::Coplanar) << "the test's solids must share no plane";
    if (s.side == Side::Front) return std::nullopt;
    if (s.side == Side::Spanning) poly = *s.back;
  }
  return poly;
}

// The parts of `poly` outside that solid, as convex pieces: in front of the first plane, or
// behind it and in front of the second, and so on.
std::vector<PlanePolygon> clip_outside(PlanePolygon poly, const std::vector<GridPlane>& solid) {
  std::vector<PlanePolygon> out;
  PredicateCounters counters;
  for (const GridPlane& plane : solid) {
    PlaneSplit s = split(poly, plane, counters);
    EXPECT_NE(s.side, Side::Coplanar) << "the test's solids must share no plane";
    if (s.side == Side::Front) {
      out.push_back(poly);
      return out;
    }
    if (s.side == Side::Spanning) {
      out.push_back(*s.front);
      poly = *s.back;
    }
  }
  return out;
}

// The boundary of `a` op `b` for convex a and b in general position: each operand's faces clipped
// to the part of it the result keeps (a difference keeps b's faces inside a, turned around).
std::vector<PlanePolygon> boundary_of(const std::vector<PlanePolygon>& a, const std::vector<PlanePolygon>& b, SetOp op) {
  const std::vector<GridPlane> pa = supports(a), pb = supports(b);
  std::vector<PlanePolygon> out;
  const auto keep_inside = [&](const std::vector<PlanePolygon>& faces, const std::vector<GridPlane>& other, bool flip) {
    for (const PlanePolygon& f : faces)
      if (const auto part = clip_inside(f, other)) out.push_back(flip ? flipped(*part) : *part);
  };
  const auto keep_outside = [&](const std::vector<PlanePolygon>& faces, const std::vector<GridPlane>& other) {
    for (const PlanePolygon& f : faces)
      for (const PlanePolygon& part : clip_outside(f, other)) out.push_back(part);
  };
  const bool a_outside = op == SetOp::Union || op == SetOp::Difference || op == SetOp::SymmetricDifference;
  const bool b_outside = op == SetOp::Union || op == SetOp::SymmetricDifference;
  if (a_outside) keep_outside(a, pb);
  if (b_outside) keep_outside(b, pa);
  if (op == SetOp::Intersection) {
    keep_inside(a, pb, false);
    keep_inside(b, pa, false);
  }
  if (op == SetOp::Difference || op == SetOp::SymmetricDifference) keep_inside(b, pa, true);
  if (op == SetOp::SymmetricDifference) keep_inside(a, pb, true);
  return out;
}

// Rationals from canonical text, for inclusion-exclusion: GMP's arithmetic on the volumes, no
// geometry.
class Rational {
 public:
  explicit Rational(const std::string& text) {
    mpq_init(q_);
    EXPECT_EQ(mpq_set_str(q_, text.c_str(), 10), 0) << text;
    mpq_canonicalize(q_);
  }
  Rational(const Rational&) = delete;
  Rational& operator=(const Rational&) = delete;
  ~Rational() { mpq_clear(q_); }

  std::string plus(const Rational& o, int sign) const {
    Rational r("0");
    if (sign > 0) mpq_add(r.q_, q_, o.q_);
    else mpq_sub(r.q_, q_, o.q_);
    return r.text();
  }
  std::string text() const {
    std::string buffer(mpz_sizeinbase(mpq_numref(q_), 10) + mpz_sizeinbase(mpq_denref(q_), 10) + 3, '\0');
    mpq_get_str(buffer.data(), 10, q_);
    return buffer.c_str();
  }
  // Whether 6 times the value is an integer, as every lattice polytope's volume is.
  bool sixths() const { return mpz_cmp_ui(mpq_denref(q_), 6) <= 0 && 6 % mpz_get_ui(mpq_denref(q_)) == 0; }

 private:
  mpq_t q_;
};

std::string sum(const std::string& a, const std::string& b) { return Rational(a).plus(Rational(b), +1); }
std::string difference(const std::string& a, const std::string& b) { return Rational(a).plus(Rational(b), -1); }

}  // namespace

TEST(ExactMeasure, BoxesAndTetrahedraHaveTheirExactVolumes) {
  const ExactBoundaryCheck unit = check_exact_boundary(plane_faces(box({0, 0, 0}, {1, 1, 1})));
  EXPECT_TRUE(unit.closed());
  EXPECT_EQ(unit.volume, "1");
  EXPECT_EQ(unit.volume_double, 1.0);
  EXPECT_EQ(unit.faces, 6u);
  EXPECT_EQ(unit.edges, 24u);
  EXPECT_EQ(unit.vertices, 8u);
  EXPECT_EQ(unit.lines, 12u);

  const Mesh slab = box({-3, 1, 0}, {2, 5, 7});
  EXPECT_EQ(check_exact_boundary(plane_faces(slab)).volume, "140");
  EXPECT_EQ(exact_mesh_volume(slab), "140");

  const Mesh corner = tetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_EQ(check_exact_boundary(plane_faces(corner)).volume, "1/6");
  EXPECT_EQ(exact_mesh_volume(corner), "1/6");

  // Sheared: |det(p1 - p0, p2 - p0, p3 - p0)| / 6 with det = 3 (4 * 5 - 2 * 1) - 1 (1 * 5 - 2 * 2) + 0 = 53.
  const Mesh sheared = tetrahedron({1, 1, 1}, {4, 2, 1}, {2, 5, 3}, {3, 2, 6});
  const ExactBoundaryCheck s = check_exact_boundary(plane_faces(sheared));
  EXPECT_TRUE(s.closed());
  EXPECT_EQ(s.volume, "53/6");
  EXPECT_EQ(exact_mesh_volume(sheared), "53/6");
}

// x >= 0, y >= 0, z >= 0, 2x + 3y + 5z <= 7: vertices (7/2, 0, 0), (0, 7/3, 0), (0, 0, 7/5) and the
// origin, none but the origin a grid point; volume (7/2)(7/3)(7/5) / 6 = 343/180.
TEST(ExactMeasure, TetrahedronWithRationalVerticesHasItsExactVolume) {
  const std::vector<PlanePolygon> faces =
      simplex_of_planes({{-1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0}, {2, 3, 5, -7}});
  const ExactBoundaryCheck r = check_exact_boundary(faces);
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.volume, "343/180");
  EXPECT_DOUBLE_EQ(r.volume_double, 343.0 / 180.0);
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.lines, 6u);
  // The same planes scaled (not canonical) make the same vertices, lines and volume.
  const std::vector<PlanePolygon> scaled =
      simplex_of_planes({{-3, 0, 0, 0}, {0, -2, 0, 0}, {0, 0, -5, 0}, {4, 6, 10, -14}});
  const ExactBoundaryCheck t = check_exact_boundary(scaled);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.volume, "343/180");
  EXPECT_EQ(t.vertices, 4u);
  EXPECT_EQ(t.lines, 6u);
}

// The top of the box [0, 6]^3 cut by the plane 3x + 2y = 7 into a triangle and a pentagon: the cut
// meets the top's edges at (7/3, 0, 6) and (0, 7/2, 6), inside the undivided top edges of the
// faces y = 0 and x = 0 (T-junctions at rational points). Closed, the same volume; without the
// triangle, three border segments: the cut, and the uncovered part of each of those two edges.
TEST(ExactMeasure, SplitFaceWithTJunctionsClosesAndMissingPartsAreCaught) {
  std::vector<PlanePolygon> faces = plane_faces(box({0, 0, 0}, {6, 6, 6}));
  const PlanePolygon top = faces[5];
  PredicateCounters counters;
  const PlaneSplit cut = split(top, GridPlane{3, 2, 0, -7}, counters);
  ASSERT_EQ(cut.side, Side::Spanning);
  faces.erase(faces.begin() + 5);
  faces.push_back(*cut.front);
  faces.push_back(*cut.back);
  const ExactBoundaryCheck whole = check_exact_boundary(faces);
  EXPECT_TRUE(whole.closed());
  EXPECT_EQ(whole.volume, "216");
  EXPECT_EQ(whole.vertices, 10u);
  EXPECT_EQ(whole.lines, 13u);

  faces.pop_back();  // the triangle, the part behind the cut (toward the origin)
  const ExactBoundaryCheck open = check_exact_boundary(faces);
  EXPECT_FALSE(open.closed());
  EXPECT_EQ(open.border_segments, 3u);
}

TEST(ExactMeasure, MissingAndFlippedFacesAreCaught) {
  const std::vector<PlanePolygon> cube = plane_faces(box({0, 0, 0}, {4, 4, 4}));
  std::vector<PlanePolygon> missing(cube.begin(), cube.end() - 1);
  EXPECT_EQ(check_exact_boundary(missing).border_segments, 4u);

  // The face y = 4 turned inward: each of its edges now doubles its neighbour's instead of
  // cancelling it, and its term of the volume, (1/3) * 4 * 16, changes sign: 64 - 128/3.
  std::vector<PlanePolygon> turned = cube;
  turned[3] = flipped(turned[3]);
  const ExactBoundaryCheck r = check_exact_boundary(turned);
  EXPECT_FALSE(r.closed());
  EXPECT_EQ(r.border_segments, 4u);
  EXPECT_EQ(r.volume, "64/3");

  // A tetrahedron with rational vertices loses a face: its three edges are left, on three lines.
  std::vector<PlanePolygon> simplex = simplex_of_planes({{-1, 0, 0, 0}, {0, -1, 0, 0}, {0, 0, -1, 0}, {2, 3, 5, -7}});
  simplex.pop_back();
  EXPECT_EQ(check_exact_boundary(simplex).border_segments, 3u);
}

TEST(ExactMeasure, PlanesPastTheGridBoundsAreRefused) {
  std::vector<PlanePolygon> faces = plane_faces(box({0, 0, 0}, {1, 1, 1}));
  faces[0].support.d = Int128{1} << 126;
  EXPECT_THROW(check_exact_boundary(faces), std::invalid_argument);
  const Mesh far = box({0, 0, 0}, {std::int64_t{1} << kGridBits, 1, 1});
  EXPECT_THROW(exact_mesh_volume(far), std::invalid_argument);
}

// Boxes sharing their y and z extent: every result is a box (or two), measured analytically.
TEST(ExactCorefine, AxisAlignedBoxesSharingFacesGiveTheKnownBoxes) {
  const Mesh a = box({0, 0, 0}, {4, 4, 4}), b = box({2, 0, 0}, {6, 4, 4});
  EXPECT_EQ(exact_corefine(a, b, SetOp::Union).volume, exact_mesh_volume(box({0, 0, 0}, {6, 4, 4})));
  EXPECT_EQ(exact_corefine(a, b, SetOp::Intersection).volume, exact_mesh_volume(box({2, 0, 0}, {4, 4, 4})));
  EXPECT_EQ(exact_corefine(a, b, SetOp::Difference).volume, exact_mesh_volume(box({0, 0, 0}, {2, 4, 4})));
  Mesh both = box({0, 0, 0}, {2, 4, 4});
  for (auto& f : box({4, 0, 0}, {6, 4, 4})) both.push_back(f);
  const ExactCorefine x = exact_corefine(a, b, SetOp::SymmetricDifference);
  EXPECT_EQ(x.volume, exact_mesh_volume(both));
  EXPECT_EQ(x.volume, "64");
  EXPECT_GT(x.triangles, 0u);
  EXPECT_GE(x.seconds, 0.0);
}

// Overlapping in all three axes: the intersection is the box [2,4] x [1,4] x [0,3].
TEST(ExactCorefine, AxisAlignedBoxesOverlappingCornersMatchInclusionExclusion) {
  const Mesh a = box({0, 0, 0}, {4, 4, 4}), b = box({2, 1, -1}, {6, 5, 3});
  const std::string va = exact_mesh_volume(a), vb = exact_mesh_volume(b);
  const std::string i = exact_corefine(a, b, SetOp::Intersection).volume;
  EXPECT_EQ(i, exact_mesh_volume(box({2, 1, 0}, {4, 4, 3})));
  EXPECT_EQ(i, "18");
  EXPECT_EQ(exact_corefine(a, b, SetOp::Union).volume, difference(sum(va, vb), i));
  EXPECT_EQ(exact_corefine(a, b, SetOp::Difference).volume, difference(va, i));
  EXPECT_EQ(exact_corefine(a, b, SetOp::SymmetricDifference).volume, difference(difference(sum(va, vb), i), i));
}

// Two sheared tetrahedra in general position whose intersection has vertices off the grid: CGAL's
// exact result, the boundary built here by clipping plane polygons (check_exact_boundary, no CGAL),
// and inclusion-exclusion agree exactly for every operation.
TEST(ExactCorefine, OffAxisTetrahedraAgreeWithIndependentBoundariesAndInclusionExclusion) {
  const Mesh a = tetrahedron({0, 0, 0}, {20, 3, 1}, {2, 19, 4}, {3, 1, 22});
  const Mesh b = tetrahedron({11, 9, 8}, {-7, 12, 3}, {9, -5, 6}, {5, 6, -9});
  const std::vector<PlanePolygon> pa = plane_faces(a), pb = plane_faces(b);
  const std::string va = exact_mesh_volume(a), vb = exact_mesh_volume(b);
  EXPECT_EQ(check_exact_boundary(pa).volume, va);
  EXPECT_EQ(check_exact_boundary(pb).volume, vb);

  std::string got[4];
  for (const SetOp op : {SetOp::Union, SetOp::Intersection, SetOp::Difference, SetOp::SymmetricDifference}) {
    const ExactCorefine c = exact_corefine(a, b, op);
    const ExactBoundaryCheck built = check_exact_boundary(boundary_of(pa, pb, op));
    EXPECT_TRUE(built.closed()) << set_op_name(op) << ": " << built.border_segments << " border segments";
    EXPECT_EQ(c.volume, built.volume) << set_op_name(op);
    got[static_cast<int>(op)] = c.volume;
  }
  const std::string& i = got[static_cast<int>(SetOp::Intersection)];
  EXPECT_FALSE(Rational(i).sixths()) << i << ": the intersection's vertices should not all be grid points";
  EXPECT_EQ(got[static_cast<int>(SetOp::Union)], difference(sum(va, vb), i));
  EXPECT_EQ(got[static_cast<int>(SetOp::Difference)], difference(va, i));
  EXPECT_EQ(got[static_cast<int>(SetOp::SymmetricDifference)], difference(difference(sum(va, vb), i), i));
}

TEST(ExactCorefine, OpenOperandIsRefused) {
  Mesh open = box({0, 0, 0}, {4, 4, 4});
  open.pop_back();
  EXPECT_THROW(exact_corefine(open, box({2, 2, 2}, {6, 6, 6}), SetOp::Union), std::runtime_error);
}
