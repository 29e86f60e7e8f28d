// OpenSCAD 2021.01's primitives, extrusions, 2D booleans and hulls (csg/openscad_shapes.h,
// csg/shapes2d.h): fragment counts and meshes equal to what /usr/bin/openscad 2021.01 exports,
// closed meshes with positive volume, exact areas and volumes.
//
// The reference OFF texts below were exported by Debian's openscad 2021.01-6 with
// `echo '<scad>' > p.scad && openscad -o p.off p.scad`; OFF prints 6 significant digits, so
// coordinates are compared within that rounding, and face index lists exactly (OpenSCAD's OFF
// numbers vertices in order of first use, as Mesh does). The 2D boolean references were exported
// from `linear_extrude(1) scale(65536) <2D op>` so that their grid coordinates print as integers.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "csg/openscad_shapes.h"
#include "csg/shapes2d.h"

using namespace bsp;
using namespace bsp::csg;

namespace {

// An OpenSCAD OFF export: its points and faces.
struct Off {
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;
};

Off parse_off(const std::string& text) {
  std::istringstream in(text);
  std::string magic;
  std::size_t nv = 0, nf = 0, ne = 0;
  in >> magic >> nv >> nf >> ne;
  Off off;
  off.points.resize(nv);
  for (Vec3& p : off.points) in >> p.x >> p.y >> p.z;
  off.faces.resize(nf);
  for (auto& f : off.faces) {
    std::size_t n = 0;
    in >> n;
    f.resize(n);
    for (auto& i : f) in >> i;
  }
  return off;
}

// Same points within OFF's 6 significant digits, same faces exactly.
void expect_matches_export(const Mesh& mesh, const std::string& off_text) {
  const Off off = parse_off(off_text);
  ASSERT_EQ(mesh.points.size(), off.points.size());
  for (std::size_t i = 0; i < off.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(mesh.points[i][k], off.points[i][k], 6e-6 * std::fabs(off.points[i][k]) + 1e-12)
          << "point " << i << " coordinate " << k;
  EXPECT_EQ(mesh.faces, off.faces);
}

// Every directed edge used once, and its reverse once: a closed, consistently oriented surface.
bool is_closed(const Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const auto& f : m.faces)
    for (std::size_t i = 0; i < f.size(); ++i) ++count[{f[i], f[(i + 1) % f.size()]}];
  for (const auto& [e, n] : count) {
    if (n != 1) return false;
    auto r = count.find({e.second, e.first});
    if (r == count.end() || r->second != 1) return false;
  }
  return !m.faces.empty();
}

// Signed volume by the divergence theorem (faces fanned from their first point).
double volume(const Mesh& m) {
  double six = 0;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      six += dot(m.points[f[0]], cross(m.points[f[i]], m.points[f[i + 1]]));
  return six / 6;
}

void expect_closed_positive(const Mesh& m, const std::string& what) {
  EXPECT_TRUE(is_closed(m)) << what;
  EXPECT_GT(volume(m), 0) << what;
}

Shape2 translated(Shape2 s, double dx, double dy) {
  for (Ring& r : s.rings)
    for (Vec2& v : r.points) v = {v.x + dx, v.y + dy};
  return s;
}

Resolution fn(double n) { return {n, 2, 12}; }

// linear_extrude's parameters, $fn = 0, $fs = 2, $fa = 12.
LinearExtrude lx(double height, bool center = false, double twist = 0, int slices = 0, Vec2 scale = {1, 1}) {
  LinearExtrude p;
  p.height = height;
  p.center = center;
  p.twist = twist;
  p.slices = slices;
  p.scale = scale;
  return p;
}

Mesh extrude(const Shape2& s, const LinearExtrude& p) { return linear_extrude(s, Triangulator(triangulate), p); }

Mesh revolve(const Shape2& s, double angle, const Resolution& res) {
  return rotate_extrude(s, triangulate(s), RotateExtrude{angle, res});
}

// The 2D points of a shape, on the 2^16 grid, as integers.
std::set<std::pair<long long, long long>> grid_points(const Shape2& s) {
  std::set<std::pair<long long, long long>> out;
  for (const Ring& r : s.rings)
    for (const Vec2& v : r.points) {
      EXPECT_EQ(v.x * kClipperScale, std::round(v.x * kClipperScale));
      EXPECT_EQ(v.y * kClipperScale, std::round(v.y * kClipperScale));
      out.insert({std::llround(v.x * kClipperScale), std::llround(v.y * kClipperScale)});
    }
  return out;
}

double triangles_area(const std::vector<Triangle2>& tris) {
  double sum = 0;
  for (const Triangle2& t : tris) sum += signed_area(Ring{{t[0], t[1], t[2]}});
  return sum;
}

}  // namespace

// ---- fragment counts ------------------------------------------------------------------------

TEST(CsgShapes, FragmentCountsFollowOpenScadRule) {
  // {r, $fn, $fs, $fa, fragments}: the point count of openscad's circle(r, $fn, $fs, $fa).
  struct Row {
    double r, fn, fs, fa;
    int n;
  };
  const Row table[] = {
      {10, 0, 2, 12, 30},        {1, 0, 2, 12, 5},          {0.5, 0, 2, 12, 5},
      {5, 0, 0.5, 5, 63},        {100, 0, 0.1, 1, 360},     {3, 0, 1, 30, 12},
      {0.0000005, 0, 2, 12, 3},  {0.000001, 0, 2, 12, 5},   {2, 7, 2, 12, 7},
      {2, 7.9, 2, 12, 7},        {2, 2, 2, 12, 3},          {2, 1, 2, 12, 3},
      {2, -3, 2, 12, 7},         {20, 0, 0.01, 0.01, 12567}, {1.5, 0, 0.3, 12, 30},
      {4.7746482927568605, 0, 1, 12, 30},                   {50, 0, 3, 7, 52},
      {7, 0, 100, 100, 5},
  };
  for (const Row& row : table) {
    const Resolution res{row.fn, row.fs, row.fa};
    EXPECT_EQ(fragments(row.r, res), row.n) << "r=" << row.r << " fn=" << row.fn << " fs=" << row.fs << " fa=" << row.fa;
    EXPECT_EQ(circle(row.r, res).rings.at(0).points.size(), std::size_t(row.n)) << "circle r=" << row.r;
  }
  // $fn inf/NaN -> 3, as OpenSCAD's get_fragments_from_r.
  EXPECT_EQ(fragments(5, {INFINITY, 2, 12}), 3);
  EXPECT_EQ(fragments(5, {NAN, 2, 12}), 3);
}

TEST(CsgShapes, FragmentCountsRefuseWhatIsNoInt) {
  EXPECT_THROW(fragments(1, {0, 0, 0}), InputError);   // 360/0 and 2 pi/0: infinitely many
  EXPECT_THROW(fragments(1, {1e12, 2, 12}), InputError);
}

TEST(CsgShapes, PrimitivesClampTinyFsAndFaLikeOpenScad) {
  // OpenSCAD clamps $fs and $fa of primitives to 0.01 (circle(r=20, $fs=0.001, $fa=0.001) has
  // 12567 points, as with 0.01).
  EXPECT_EQ(circle(20, {0, 0.001, 0.001}).rings[0].points.size(), 12567u);
}

TEST(CsgShapes, TwistedExtrusionSlicesFollowOpenScadRule) {
  // linear_extrude(height=10, twist=90) square(5): 8 slices (8 * 4 * 2 wall triangles + 4 caps).
  EXPECT_EQ(extrude(square({5, 5}, false), lx(10, false, 90)).faces.size(), 68u);
  EXPECT_EQ(helix_slices(50, 10, 90, {}), 8);
  EXPECT_EQ(helix_slices(50, 10, 90, fn(16)), 4);        // ceil(90 / 360 * 16)
  EXPECT_EQ(helix_slices(0, 10, 500, {}), 5);             // r = 0: ceil(500 / 120)
  EXPECT_EQ(diagonal_slices(1, 10, fn(6)), 6);
}

// ---- identity with OpenSCAD's export ---------------------------------------------------------

TEST(CsgShapes, SphereMatchesOpenScadExport) {
  // sphere(r=2,$fn=5);
  expect_matches_export(sphere(2, fn(5)), R"(OFF 15 22 0
1 0 1.73205 
0.309017 0.951057 1.73205 
-0.809017 0.587785 1.73205 
-0.809017 -0.587785 1.73205 
0.309017 -0.951057 1.73205 
2 0 0 
0.618034 1.90211 0 
-1.61803 1.17557 0 
-1.61803 -1.17557 0 
0.618034 -1.90211 0 
1 0 -1.73205 
0.309017 0.951057 -1.73205 
-0.809017 0.587785 -1.73205 
-0.809017 -0.587785 -1.73205 
0.309017 -0.951057 -1.73205 
5 0 1 2 3 4
3 5 6 0
3 6 1 0
3 6 7 1
3 7 2 1
3 7 8 2
3 8 3 2
3 8 9 3
3 9 4 3
3 9 5 4
3 5 0 4
3 10 11 5
3 11 6 5
3 11 12 6
3 12 7 6
3 12 13 7
3 13 8 7
3 13 14 8
3 14 9 8
3 14 10 9
3 10 5 9
5 14 13 12 11 10
)");
  // sphere(r=1); (default $fs = 2, $fa = 12: 5 fragments, 3 rings)
  expect_matches_export(sphere(1, {}), R"(OFF 15 22 0
0.5 0 0.866025 
0.154508 0.475528 0.866025 
-0.404508 0.293893 0.866025 
-0.404508 -0.293893 0.866025 
0.154508 -0.475528 0.866025 
1 0 0 
0.309017 0.951057 0 
-0.809017 0.587785 0 
-0.809017 -0.587785 0 
0.309017 -0.951057 0 
0.5 0 -0.866025 
0.154508 0.475528 -0.866025 
-0.404508 0.293893 -0.866025 
-0.404508 -0.293893 -0.866025 
0.154508 -0.475528 -0.866025 
5 0 1 2 3 4
3 5 6 0
3 6 1 0
3 6 7 1
3 7 2 1
3 7 8 2
3 8 3 2
3 8 9 3
3 9 4 3
3 9 5 4
3 5 0 4
3 10 11 5
3 11 6 5
3 11 12 6
3 12 7 6
3 12 13 7
3 13 8 7
3 13 14 8
3 14 9 8
3 14 10 9
3 10 5 9
5 14 13 12 11 10
)");
}

TEST(CsgShapes, CylinderMatchesOpenScadExport) {
  // cylinder(h=3,r1=2,r2=0,center=true,$fn=5);  (a cone: one apex point)
  expect_matches_export(cylinder(3, 2, 0, true, fn(5)), R"(OFF 6 6 0
0.618034 1.90211 -1.5 
0 0 1.5 
2 0 -1.5 
-1.61803 1.17557 -1.5 
-1.61803 -1.17557 -1.5 
0.618034 -1.90211 -1.5 
3 0 1 2
3 3 1 0
3 4 1 3
3 5 1 4
3 2 1 5
5 5 4 3 0 2
)");
  // cylinder(h=2,r=1.5,$fn=4);  (quads)
  expect_matches_export(cylinder(2, 1.5, 1.5, false, fn(4)), R"(OFF 8 6 0
0 1.5 0 
0 1.5 2 
1.5 0 2 
1.5 0 0 
-1.5 -0 0 
-1.5 -0 2 
-0 -1.5 0 
-0 -1.5 2 
4 0 1 2 3
4 4 5 1 0
4 6 7 5 4
4 3 2 7 6
4 6 4 0 3
4 2 1 5 7
)");
}

TEST(CsgShapes, CubeMatchesOpenScadExport) {
  // cube([1,2,3],center=true);
  expect_matches_export(cube({1, 2, 3}, true), R"(OFF 8 6 0
-0.5 -1 1.5 
0.5 -1 1.5 
0.5 1 1.5 
-0.5 1 1.5 
-0.5 1 -1.5 
0.5 1 -1.5 
0.5 -1 -1.5 
-0.5 -1 -1.5 
4 0 1 2 3
4 4 5 6 7
4 7 6 1 0
4 6 5 2 1
4 5 4 3 2
4 4 7 0 3
)");
}

TEST(CsgShapes, LinearExtrudeMatchesOpenScadExport) {
  // linear_extrude(height=2,twist=90,slices=2,scale=0.5) square(1);
  expect_matches_export(extrude(square({1, 1}, false), lx(2, false, 90, 2, {0.5, 0.5})), R"(OFF 12 20 0
1 0 0 
0 0 0 
0 1 0 
1 1 0 
0.5 -0.5 2 
0 0 2 
0 -0.5 2 
0.5 0 2 
0.53033 -0.53033 1 
0 0 1 
1.06066 0 1 
0.53033 0.53033 1 
3 0 1 2
3 0 2 3
3 4 5 6
3 4 7 5
3 0 8 1
3 9 1 8
3 3 10 0
3 8 0 10
3 2 11 3
3 10 3 11
3 1 11 2
3 1 9 11
3 8 6 9
3 5 9 6
3 10 4 8
3 6 8 4
3 11 7 10
3 4 10 7
3 9 7 11
3 9 5 7
)");
}

TEST(CsgShapes, RotateExtrudeMatchesOpenScadExport) {
  // rotate_extrude(angle=90,$fn=4) translate([1,0]) square([1,2]);
  expect_matches_export(revolve(translated(square({1, 2}, false), 1, 0), 90, fn(4)), R"(OFF 8 12 0
1 0 2 
1 0 0 
2 0 0 
2 0 2 
0 2 0 
0 1 0 
0 1 2 
0 2 2 
3 0 1 2
3 3 0 2
3 4 5 6
3 4 6 7
3 3 7 0
3 7 6 0
3 2 4 3
3 4 7 3
3 1 5 2
3 5 4 2
3 0 6 1
3 6 5 1
)");
}

TEST(CsgShapes, Hull3MatchesOpenScadExport) {
  // hull(){cube([1,2,3]);}: OpenSCAD hulls the cube's face vertices in face order.
  std::vector<Vec3> pts;
  const Mesh c = cube({1, 2, 3}, false);
  for (const auto& f : c.faces)
    for (auto i : f) pts.push_back(c.points[i]);
  expect_matches_export(hull3(pts), R"(OFF 8 12 0
1 2 3 
0 2 3 
1 0 3 
0 0 0 
0 0 3 
1 0 0 
1 2 0 
0 2 0 
3 0 1 2
3 1 3 4
3 5 6 2
3 2 1 4
3 3 6 5
3 7 3 1
3 1 6 7
3 7 6 3
3 2 3 5
3 4 3 2
3 0 6 1
3 2 6 0
)");
}

TEST(CsgShapes, Boolean2MatchesOpenScadGridVertices) {
  // linear_extrude(1) scale(65536) union(){circle(5,$fn=7); translate([0.1,0.05]) circle(5,$fn=8);}
  const std::set<std::pair<long long, long long>> union_ref = {
      {212546, -239077}, {130643, -273003},  {334233, 3276},      {204305, -256190},  {208603, 247264},
      {238258, 234981},  {238258, -228427},  {165883, 264960},    {204305, 256190},   {-39567, 311852},
      {6553, 330956},    {-128817, 274884},  {-72915, 319464},    {-295229, 65797},   {-247987, 179849},
      {-225151, 234981}, {-295229, -59245},  {-295229, 142175},   {-145917, -261247}, {-321126, 3276},
      {-243934, -183081}, {-295229, -142175}, {6553, -324403},    {-29367, -309524},  {-225151, -228427},
      {-72915, -319464}};
  EXPECT_EQ(grid_points(boolean2(Op2::Union, {circle(5, fn(7)), translated(circle(5, fn(8)), 0.1, 0.05)})),
            union_ref);
  // ... difference(){square(10,center=true); translate([-0.1,0.2]) circle(3,$fn=12);}
  const std::set<std::pair<long long, long long>> difference_ref = {
      {-327680, 327680}, {-6553, 209715},   {-104857, 183374}, {327680, 327680},  {190054, 13107},
      {163713, 111411},  {327680, -327680}, {-6553, -183500},  {91750, -157160},  {-327680, -327680},
      {-104857, -157160}, {-203161, 13107}, {-176821, -85196}, {-176821, 111411}, {91750, 183374},
      {163713, -85196}};
  const Shape2 d = boolean2(Op2::Difference, {square({10, 10}, true), translated(circle(3, fn(12)), -0.1, 0.2)});
  EXPECT_EQ(grid_points(d), difference_ref);
  ASSERT_EQ(d.rings.size(), 2u);  // outer counter-clockwise, hole clockwise
  EXPECT_GT(std::max(signed_area(d.rings[0]), signed_area(d.rings[1])), 0);
  EXPECT_LT(std::min(signed_area(d.rings[0]), signed_area(d.rings[1])), 0);
}

// ---- closed meshes ---------------------------------------------------------------------------

TEST(CsgShapes, EveryMeshIsClosedWithPositiveVolume) {
  for (double r : {0.5, 1.0, 3.0, 10.0})
    for (double n : {0.0, 3.0, 4.0, 5.0, 7.0, 12.0, 30.0}) {
      const std::string what = "r=" + std::to_string(r) + " fn=" + std::to_string(n);
      expect_closed_positive(sphere(r, fn(n)), "sphere " + what);
      for (bool center : {false, true}) {
        expect_closed_positive(cylinder(2, r, r, center, fn(n)), "cylinder " + what);
        expect_closed_positive(cylinder(2, r, 0, center, fn(n)), "cone r2=0 " + what);
        expect_closed_positive(cylinder(2, 0, r, center, fn(n)), "cone r1=0 " + what);
        expect_closed_positive(cylinder(2, r, r / 3, center, fn(n)), "frustum " + what);
      }
    }
  expect_closed_positive(cube({1, 2, 3}, false), "cube");
  expect_closed_positive(cube({1, 2, 3}, true), "centred cube");

  const Shape2 annulus = boolean2(Op2::Difference, {circle(3, {}), square({2, 2}, true)});
  const Shape2 shapes[] = {square({2, 3}, false), square({2, 3}, true), circle(2.5, {}), annulus};
  const Vec2 scales[] = {{1, 1}, {0.5, 0.5}, {0, 0}, {2, 2}, {0.3, 2}, {1.7, 0.4}};
  for (const Shape2& s : shapes)
    for (double twist : {0.0, 45.0, -200.0, 360.0})
      for (const Vec2& sc : scales)
        for (int slices : {0, 3}) {
          const LinearExtrude p = lx(5, twist < 0, twist, slices, sc);
          const std::string what = "linear_extrude twist=" + std::to_string(twist) + " scale=" +
                                   std::to_string(sc.x) + "," + std::to_string(sc.y) + " slices=" + std::to_string(slices);
          expect_closed_positive(extrude(s, p), what);
          expect_closed_positive(linear_extrude(s, triangulate(s), p), what + " (caller's cap)");
        }

  const Shape2 profiles[] = {translated(square({1, 2}, false), 1, -1), translated(circle(0.8, {}), 2, 0),
                             square({1, 2}, false) /* touching the axis */,
                             translated(annulus, 4, 0), translated(square({1, 2}, false), -3, 0)};
  for (const Shape2& s : profiles)
    for (double angle : {360.0, 90.0, -90.0, 250.0, 45.0, -359.0})
      for (double n : {0.0, 5.0, 16.0})
        expect_closed_positive(revolve(s, angle, fn(n)), "rotate_extrude angle=" + std::to_string(angle));
}

// ---- exact volumes and areas -----------------------------------------------------------------

TEST(CsgShapes, LinearExtrudeOfSquareHasAreaTimesHeight) {
  EXPECT_DOUBLE_EQ(volume(extrude(square({2, 3}, false), lx(7))), 42.0);
  EXPECT_DOUBLE_EQ(volume(extrude(square({2, 3}, true), lx(7, true))), 42.0);
  // Uniform scale about the origin: a frustum, h/3 (A + A s^2 + A s) with planar sides.
  EXPECT_NEAR(volume(extrude(square({2, 2}, true), lx(6, false, 0, 0, {0.5, 0.5}))), 6.0 / 3 * (4 + 1 + 2), 1e-12);
  // Scale 0: a pyramid, A h / 3, whatever the twist.
  EXPECT_NEAR(volume(extrude(square({2, 2}, true), lx(6, false, 0, 0, {0, 0}))), 8.0, 1e-12);
  const Mesh apex = extrude(square({2, 2}, true), lx(6, false, 0, 0, {0, 0}));
  EXPECT_EQ(apex.points.size(), 5u);  // OpenSCAD: a single apex point
}

TEST(CsgShapes, RotateExtrudeOfRectangleHasPolygonalAnnulusVolume) {
  // Rectangle [a, b] x [0, h] revolved in n steps of angle t: each step is a prism over the
  // difference of two isosceles triangles, (b^2 - a^2) sin(t) / 2 * h.
  const double a = 1.5, b = 4, h = 2;
  const Shape2 rect = translated(square({b - a, h}, false), a, 0);
  for (double angle : {360.0, 90.0, 250.0, -120.0})
    for (double n : {0.0, 7.0, 40.0}) {
      const int full = fragments(b, fn(n));
      const int steps = std::max(int(full * std::fabs(angle) / 360), 1);
      const double t = std::fabs(angle) / steps * M_PI / 180;
      const double expected = steps * (b * b - a * a) * std::sin(t) / 2 * h;
      EXPECT_NEAR(volume(revolve(rect, angle, fn(n))), expected, 1e-9 * expected) << "angle " << angle << " fn " << n;
    }
}

TEST(CsgShapes, Boolean2AreasOfOverlappingSquares) {
  const Shape2 a = square({2, 2}, false), b = translated(square({2, 2}, false), 1, 1);
  const Shape2 c = translated(square({2, 2}, false), -1, 1);
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Union, {a, b})), 7.0);
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Intersection, {a, b})), 1.0);
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Difference, {a, b})), 3.0);
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Difference, {a, b, c})), 2.0);   // first minus the rest
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Union, {a, b, c})), 10.0);
  EXPECT_DOUBLE_EQ(area(boolean2(Op2::Intersection, {a, b, c})), 0.0);
  EXPECT_TRUE(boolean2(Op2::Intersection, {a, b, c}).empty());
  // A hole: outer ring counter-clockwise, hole clockwise, area 16 - 4.
  const Shape2 frame = boolean2(Op2::Difference, {square({4, 4}, true), square({2, 2}, true)});
  EXPECT_DOUBLE_EQ(area(frame), 12.0);
  ASSERT_EQ(frame.rings.size(), 2u);
  // One operand is returned as is (OpenSCAD copies a lone child), none gives nothing.
  EXPECT_EQ(boolean2(Op2::Union, {circle(1, {})}).rings[0].points, circle(1, {}).rings[0].points);
  EXPECT_TRUE(boolean2(Op2::Union, {}).empty());
}

TEST(CsgShapes, Boolean2TruncatesInputToClipperGrid) {
  // 0.1 * 2^16 = 6553.6 -> 6553 and -0.05 * 2^16 = -3276.8 -> -3276 (toward zero, as Clipper).
  const Shape2 s = boolean2(Op2::Union, {translated(square({0.1, 0.1}, false), -0.05, 0), Shape2{}});
  const auto pts = grid_points(s);
  EXPECT_TRUE(pts.count({-3276, 0}));
  EXPECT_TRUE(pts.count({3276, 6553}));
}

TEST(CsgShapes, Sanitize2FillsEvenOdd) {
  // polygon() with a second path inside the first: a hole (OpenSCAD's sanitize is even-odd).
  const Shape2 nested = sanitize2(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}, {2, 2}, {8, 2}, {8, 8}, {2, 8}},
                                         {{0, 1, 2, 3}, {4, 5, 6, 7}}));
  EXPECT_DOUBLE_EQ(area(nested), 64.0);
  // A bow tie crossing itself at (1, 1): two triangles of area 1 each.
  const Shape2 bowtie = sanitize2(polygon({{0, 0}, {2, 2}, {2, 0}, {0, 2}}, {}));
  EXPECT_DOUBLE_EQ(area(bowtie), 2.0);
  EXPECT_EQ(bowtie.rings.size(), 2u);
  // Clockwise input comes out counter-clockwise.
  const Shape2 cw = sanitize2(polygon({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, {}));
  EXPECT_DOUBLE_EQ(area(cw), 1.0);
}

TEST(CsgShapes, TriangulateCoversSquareWithHole) {
  const Shape2 frame = boolean2(Op2::Difference, {square({10, 10}, true), square({6, 6}, true)});
  const std::vector<Triangle2> tris = triangulate(frame);
  EXPECT_DOUBLE_EQ(triangles_area(tris), 64.0);
  std::set<std::pair<double, double>> own;
  for (const Ring& r : frame.rings)
    for (const Vec2& v : r.points) own.insert({v.x, v.y});
  for (const Triangle2& t : tris) {
    EXPECT_GT(signed_area(Ring{{t[0], t[1], t[2]}}), 0);  // counter-clockwise
    for (const Vec2& v : t) EXPECT_TRUE(own.count({v.x, v.y}));
  }
}

TEST(CsgShapes, Hull2IsConvexHullOfAllPoints) {
  const Shape2 h = hull2({square({1, 1}, false), translated(square({1, 1}, false), 3, 0)});
  ASSERT_EQ(h.rings.size(), 1u);
  EXPECT_EQ(h.rings[0].points.size(), 4u);
  EXPECT_DOUBLE_EQ(area(h), 4.0);
  EXPECT_TRUE(hull2({polygon({{0, 0}, {1, 1}, {2, 2}}, {})}).empty());  // collinear: no area
}

TEST(CsgShapes, Hull3OfCubeCornersIsCube) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  const Mesh h = hull3(corners);
  EXPECT_EQ(h.points.size(), 8u);
  EXPECT_EQ(h.faces.size(), 12u);
  EXPECT_TRUE(is_closed(h));
  EXPECT_DOUBLE_EQ(volume(h), 1.0);
  std::set<std::tuple<double, double, double>> got, want;
  for (const Vec3& p : h.points) got.insert({p.x, p.y, p.z});
  for (const Vec3& p : corners) want.insert({p.x, p.y, p.z});
  EXPECT_EQ(got, want);
  // Flat or too few points: no 3D object.
  EXPECT_TRUE(hull3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}).faces.empty());
  EXPECT_TRUE(hull3({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}).faces.empty());
  EXPECT_TRUE(hull3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).faces.empty());
}

// ---- refusals and degenerate input -------------------------------------------------------------

TEST(CsgShapes, RotateExtrudeRefusesShapeOnBothSidesOfAxis) {
  const Shape2 across = translated(square({4, 1}, false), -2, 0);
  EXPECT_THROW(revolve(across, 360, {}), InputError);
  try {
    revolve(across, 360, {});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("same X coordinate sign"), std::string::npos) << e.what();
  }
}

TEST(CsgShapes, DegenerateInputsGiveEmptyMesh) {
  EXPECT_TRUE(sphere(0, {}).faces.empty());
  EXPECT_TRUE(sphere(-1, {}).faces.empty());
  EXPECT_TRUE(sphere(INFINITY, {}).faces.empty());
  EXPECT_TRUE(cylinder(0, 1, 1, false, {}).faces.empty());
  EXPECT_TRUE(cylinder(1, 0, 0, false, {}).faces.empty());
  EXPECT_TRUE(cylinder(1, -1, 2, false, {}).faces.empty());
  EXPECT_TRUE(cube({1, 0, 1}, false).faces.empty());
  EXPECT_TRUE(circle(0, {}).empty());
  EXPECT_TRUE(square({1, -1}, false).empty());
  EXPECT_TRUE(polygon({{0, 0}, {1, 1}}, {}).empty());
  EXPECT_TRUE(extrude(square({1, 1}, false), lx(0)).faces.empty());
  EXPECT_TRUE(extrude(Shape2{}, lx(5)).faces.empty());
  EXPECT_TRUE(revolve(translated(square({1, 1}, false), 1, 0), 0, {}).faces.empty());
  EXPECT_TRUE(revolve(Shape2{}, 360, {}).faces.empty());
}
