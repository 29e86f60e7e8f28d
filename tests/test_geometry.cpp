// Classification and splitting of convex polygons: area is preserved, attributes interpolate
// linearly, slivers are dropped and counted.
#include <gtest/gtest.h>

#include "geometry/polygon.h"
#include "geometry/point_grid.h"
#include "geometry/polytope.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "common/page_allocator.h"
#include "common/rng.h"
#include "geometry/tolerance.h"

using namespace bsp;

namespace {

Polygon unit_square() {
  return {{{{0, 0, 0}, 0, 0}, {{1, 0, 0}, 1, 0}, {{1, 1, 0}, 1, 1}, {{0, 1, 0}, 0, 1}}, 7};
}

const double kEps = Tolerance::for_extent(1.0).plane_eps;

}  // namespace

TEST(Classify, FrontBackCoplanarSpanning) {
  const Polygon sq = unit_square();
  EXPECT_EQ(classify(sq, Plane::through({0, 0, 1}, {0, 0, -1}), kEps), Side::Front);
  EXPECT_EQ(classify(sq, Plane::through({0, 0, 1}, {0, 0, 1}), kEps), Side::Back);
  EXPECT_EQ(classify(sq, Plane::through({0, 0, -1}, {0, 0, 0}), kEps), Side::Coplanar);
  EXPECT_EQ(classify(sq, Plane::through({1, 0, 0}, {0.5, 0, 0}), kEps), Side::Spanning);
}

TEST(Classify, VertexWithinToleranceCountsAsOnThePlane) {
  Polygon sq = unit_square();
  sq.verts[2].p.z = 0.5 * kEps;  // nearly coplanar: still coplanar
  EXPECT_EQ(classify(sq, Plane::through({0, 0, 1}, {0, 0, 0}), kEps), Side::Coplanar);
  sq.verts[2].p.z = 2 * kEps;
  EXPECT_EQ(classify(sq, Plane::through({0, 0, 1}, {0, 0, 0}), kEps), Side::Front);
}

TEST(Split, PreservesAreaAndSource) {
  const Polygon sq = unit_square();
  const auto r = split(sq, Plane::through({1, 1, 0}, {0.7, 0.1, 0}), kEps);
  ASSERT_TRUE(r.front && r.back);
  EXPECT_NEAR(area(*r.front) + area(*r.back), 1.0, 1e-12);
  EXPECT_EQ(r.front->source, 7u);
  EXPECT_EQ(r.back->source, 7u);
  EXPECT_EQ(r.dropped, 0);
}

TEST(Split, InterpolatesTextureCoordinatesLinearly) {
  // On the unit square u = x and v = y, so every vertex of every part must keep that relation.
  const auto r = split(unit_square(), Plane::through({1, 0.3, 0}, {0.37, 0.5, 0}), kEps);
  ASSERT_TRUE(r.front && r.back);
  for (const auto* part : {&*r.front, &*r.back})
    for (const auto& v : part->verts) {
      EXPECT_NEAR(v.u, v.p.x, 1e-12);
      EXPECT_NEAR(v.v, v.p.y, 1e-12);
    }
}

TEST(Split, PartsLieOnTheirSides) {
  const Plane plane = Plane::through({0.2, 1, 0.1}, {0.5, 0.5, 0});
  const auto r = split(unit_square(), plane, kEps);
  ASSERT_TRUE(r.front && r.back);
  EXPECT_TRUE(in_front_or_on(*r.front, plane, kEps));
  EXPECT_TRUE(in_front_or_on(*r.back, plane.flipped(), kEps));
}

TEST(Split, SliverBelowToleranceIsDroppedAndCounted) {
  // A diagonal plane 1.5 eps inside the corner (1,1): the square spans it, and the corner's part
  // is a right isosceles triangle whose width (area / longest edge) is 0.75 eps: a sliver.
  const Vec3 n = normalize(Vec3{1, 1, 0});
  const auto r = split(unit_square(), Plane::through(n, Vec3{1, 1, 0} - n * (1.5 * kEps)), kEps);
  ASSERT_TRUE(r.back);
  EXPECT_FALSE(r.front);
  EXPECT_EQ(r.dropped, 1);
  EXPECT_NEAR(r.dropped_area, 2.25 * kEps * kEps, 1e-3 * kEps * kEps);
  EXPECT_NEAR(area(*r.back) + r.dropped_area, 1.0, 1e-12);
}

TEST(PlanePool, StoresEachPlaneWithItsFlip) {
  PlanePool pool;
  const Plane p = Plane::through({0, 0, 1}, {0, 0, 2});
  const auto a = pool.add(p);
  EXPECT_EQ(pool.add(p), a);
  EXPECT_EQ(pool.add(p.flipped()), PlanePool::flip(a));
  EXPECT_TRUE(PlanePool::coplanar(a, PlanePool::flip(a)));
  const auto b = pool.add(Plane::through({0, 0, 1}, {0, 0, 3}));
  EXPECT_FALSE(PlanePool::coplanar(a, b));
  // The flip is read as the exact negation, and only one plane per pair is stored.
  EXPECT_EQ(pool[a], p);
  EXPECT_EQ(pool[PlanePool::flip(a)], p.flipped());
  EXPECT_EQ(pool.size(), 4u);
  EXPECT_EQ(pool.bytes(), 2 * sizeof(Plane));
}

// The lookup table grows (64 slots at first) and compares a tag of the hash before a plane: each of
// 20,000 planes, among them pairs that differ in one component or only in the sign of a zero, keeps
// one index in each orientation, however many times and in whichever orientation it comes back.
TEST(PlanePool, FindsEveryPlaneAndItsFlipAfterTheTableGrows) {
  Rng rng(7);
  std::vector<Plane> planes;
  for (int i = 0; i < 10000; ++i) {
    const Plane p = Plane::through(normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5}),
                                   {rng.uniform(), rng.uniform(), rng.uniform()});
    planes.push_back(p);
    planes.push_back({p.n, std::nextafter(p.d, 2.0)});  // a neighbour in one bit of d
  }
  planes.push_back({{0, 0, 1}, 0.0});
  PlanePool pool;
  std::vector<std::uint32_t> index;
  for (const Plane& p : planes) index.push_back(pool.add(p));
  EXPECT_EQ(pool.size(), 2 * planes.size());
  EXPECT_EQ(pool.add({{0, 0, 1}, -0.0}), index.back());  // -0 equals +0
  for (std::size_t i = 0; i < planes.size(); ++i) {
    EXPECT_EQ(index[i], 2 * i);
    EXPECT_EQ(pool.add(planes[i].flipped()), PlanePool::flip(index[i]));
    EXPECT_EQ(pool.add(planes[i], PlanePool::hash(planes[i])), index[i]);
  }
  EXPECT_EQ(pool.size(), 2 * planes.size());
}

// The grid's table grows from 64 slots as cells fill: after 20,000 points in about 3,200 cells,
// each query around a point reports exactly the points of the 27 cells around it (against a scan of
// all), each once; so does a query of the cells a box meets, which declines a box of more cells
// than it is allowed to read.
TEST(PointGrid, ReportsEveryPointOfTheNeighbouringCellsAfterGrowing) {
  Rng rng(11);
  const double cell = 0.05;
  std::vector<Vec3> pts;
  PointGrid grid(cell);
  for (std::uint32_t i = 0; i < 20000; ++i) {
    pts.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-0.05, 0.05)});
    grid.insert(pts.back(), i);
  }
  const auto cell_of = [&](const Vec3& p) {
    return std::array<double, 3>{std::floor(p.x / cell), std::floor(p.y / cell), std::floor(p.z / cell)};
  };
  for (std::uint32_t q = 0; q < pts.size(); q += 97) {
    const auto c = cell_of(pts[q]);
    std::vector<std::uint32_t> expected, got;
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      const auto d = cell_of(pts[i]);
      if (std::abs(d[0] - c[0]) <= 1 && std::abs(d[1] - c[1]) <= 1 && std::abs(d[2] - c[2]) <= 1) expected.push_back(i);
    }
    grid.around(pts[q], [&](std::uint32_t id) { got.push_back(id); });
    std::vector<std::uint32_t> sorted = got;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, expected) << q;
    // The box from the point to 2.5 cells beyond it in x and y meets 4 x 4 x 1 or 2 cells.
    const Vec3 lo = pts[q], hi = pts[q] + Vec3{2.5 * cell, 2.5 * cell, 0};
    const auto d0 = cell_of(lo), d1 = cell_of(hi);
    std::vector<std::uint32_t> in_cells, boxed;
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      const auto d = cell_of(pts[i]);
      if (d[0] >= d0[0] && d[0] <= d1[0] && d[1] >= d0[1] && d[1] <= d1[1] && d[2] >= d0[2] && d[2] <= d1[2])
        in_cells.push_back(i);
    }
    EXPECT_FALSE(grid.in_box(lo, hi, 8, [&](std::uint32_t id) { boxed.push_back(id); }));
    EXPECT_TRUE(boxed.empty());
    EXPECT_TRUE(grid.in_box(lo, hi, 64, [&](std::uint32_t id) { boxed.push_back(id); }));
    std::sort(boxed.begin(), boxed.end());
    EXPECT_EQ(boxed, in_cells) << q;
  }
}

TEST(ConvexPolytope, BoxVolumeAndArea) {
  const auto box = ConvexPolytope::box({{0, 0, 0}, {1, 2, 3}});
  EXPECT_NEAR(box.volume(), 6.0, 1e-12);
  EXPECT_NEAR(box.surface_area(), 22.0, 1e-12);
}

TEST(ConvexPolytope, ClippingAtACornerLeavesATetrahedron) {
  // x + y + z >= 2.5 keeps the corner (1,1,1) of the unit cube: a tetrahedron with legs 0.5.
  const auto cube = ConvexPolytope::box({{0, 0, 0}, {1, 1, 1}});
  const Vec3 n = normalize(Vec3{1, 1, 1});
  const auto corner = cube.clipped(Plane::through(n, {2.5 / 3, 2.5 / 3, 2.5 / 3}), 1e-12);
  EXPECT_NEAR(corner.volume(), 0.125 / 6, 1e-12);
  const auto rest = cube.clipped(Plane::through(-n, {2.5 / 3, 2.5 / 3, 2.5 / 3}), 1e-12);
  EXPECT_NEAR(rest.volume() + corner.volume(), 1.0, 1e-12);
  // Three right triangles with legs 0.5 plus an equilateral cap with side 0.5 sqrt(2).
  const double cap = std::sqrt(3.0) / 4 * 0.5;
  EXPECT_NEAR(corner.surface_area(), 3 * 0.125 + cap, 1e-12);
}

TEST(ConvexPolytope, ClippingByAPlaneOutsideKeepsAllOrNothing) {
  const auto cube = ConvexPolytope::box({{0, 0, 0}, {1, 1, 1}});
  EXPECT_NEAR(cube.clipped(Plane::through({0, 0, 1}, {0, 0, -1}), 1e-12).volume(), 1.0, 1e-12);
  EXPECT_TRUE(cube.clipped(Plane::through({0, 0, 1}, {0, 0, 2}), 1e-12).empty());
}

// measure_split gives what building both parts with clipped() and measuring them gives: on seeded
// random cells (a box cut by up to 8 random planes) and random planes through them, and where the
// plane misses the cell, touches it at a face, or passes through its vertices.
TEST(ConvexPolytope, MeasuringASplitEqualsMeasuringBothClippedParts) {
  Rng rng(17);
  const auto random_unit = [&] { return normalize(Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}); };
  const auto random_point = [&] { return Vec3{rng.uniform(), rng.uniform(), rng.uniform()}; };
  const double eps = 1e-12;
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    ConvexPolytope cell = ConvexPolytope::box({{0, 0, 0}, {1, 1, 1}});
    const int cuts = trial % 9;
    for (int c = 0; c < cuts; ++c) {
      const ConvexPolytope next = cell.clipped(Plane::through(random_unit(), random_point()), eps);
      if (next.volume() > 1e-3) cell = next;
    }
    std::vector<Plane> planes = {Plane::through(random_unit(), random_point()), Plane::through({0, 0, 1}, {0, 0, 0}),
                                 Plane::through({0, 0, -1}, {0, 0, 2})};
    const Vec3 corner = cell.face(0).front();
    planes.push_back(Plane::through(random_unit(), corner));
    for (const Plane& p : planes) {
      const auto m = cell.measure_split(p, eps);
      const ConvexPolytope front = cell.clipped(p, eps), back = cell.clipped(p.flipped(), eps);
      const double scale = cell.surface_area();
      EXPECT_NEAR(m.front_volume, front.volume(), 1e-9) << trial;
      EXPECT_NEAR(m.back_volume, back.volume(), 1e-9) << trial;
      EXPECT_NEAR(m.front_area, front.surface_area(), 1e-9 * scale) << trial;
      EXPECT_NEAR(m.back_area, back.surface_area(), 1e-9 * scale) << trial;
      // Volumes alone are the same bits, without the areas.
      const auto v = cell.measure_split(p, eps, ConvexPolytope::Measures::Volumes);
      EXPECT_EQ(v.front_volume, m.front_volume) << trial;
      EXPECT_EQ(v.back_volume, m.back_volume) << trial;
      EXPECT_EQ(v.front_area + v.back_area, 0.0) << trial;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1200);
}

// clip_into a polytope that already holds another (larger, smaller, the same) gives clipped()'s
// faces exactly: its memory is reused, never its contents.
TEST(ConvexPolytope, ClippingIntoAUsedPolytopeEqualsClippingIntoAFreshOne) {
  Rng rng(23);
  const auto random_plane = [&] {
    return Plane::through(normalize(Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}),
                          Vec3{rng.uniform(), rng.uniform(), rng.uniform()});
  };
  const auto same = [](const ConvexPolytope& a, const ConvexPolytope& b) {
    if (a.face_count() != b.face_count()) return false;
    for (std::size_t i = 0; i < a.face_count(); ++i)
      if (!std::equal(a.face(i).begin(), a.face(i).end(), b.face(i).begin(), b.face(i).end(),
                      [](const Vec3& p, const Vec3& q) { return p.x == q.x && p.y == q.y && p.z == q.z; }))
        return false;
    return true;
  };
  ConvexPolytope used = ConvexPolytope::box({{-5, -5, -5}, {5, 5, 5}});
  int cut = 0;
  for (int trial = 0; trial < 200; ++trial) {
    ConvexPolytope cell = ConvexPolytope::box({{0, 0, 0}, {1, 1, 1}});
    for (int c = 0; c < trial % 6; ++c) cell = cell.clipped(random_plane(), 1e-12);
    const Plane p = trial % 7 == 0 ? Plane::through({0, 0, 1}, {0, 0, 2}) : random_plane();  // some miss the cell
    const ConvexPolytope fresh = cell.clipped(p, 1e-12);
    cell.clip_into(p, 1e-12, used);
    EXPECT_TRUE(same(used, fresh)) << trial;
    cut += !fresh.empty() && fresh.face_count() != cell.face_count();
  }
  EXPECT_GT(cut, 50);
}

TEST(Split, AdjacentVerticesWithinToleranceDoNotMakeThePartsOverlap) {
  // A square tilted so its vertices lie at +2, +0.5, -0.5, -2 eps from the plane: it spans the plane,
  // and the two middle vertices are within eps of it. The parts must add up to the square.
  const double e = kEps;
  const Polygon tilted{{{{0, 0, 2 * e}, 0, 0}, {{1, 0, 0.5 * e}, 1, 0}, {{1, 1, -2 * e}, 1, 1}, {{0, 1, -0.5 * e}, 0, 1}}, 0};
  const auto r = split(tilted, Plane::through({0, 0, 1}, {0, 0, 0}), e);
  const double parts = (r.front ? area(*r.front) : 0.0) + (r.back ? area(*r.back) : 0.0) + r.dropped_area;
  EXPECT_NEAR(parts, area(tilted), 1e-12);
}

// Mesh faces share vertices: a plane made from one face passes through a vertex of its neighbour
// up to rounding, so the neighbour's cut point next to that vertex lands within rounding of it,
// often exactly on it. No part may keep two vertices within plane_eps, and the area adds up.
TEST(Split, ACutPointRoundingOntoASharedVertexIsNotRepeated) {
  Rng rng(11);
  const auto point = [&] { return Vec3{rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 4)}; };
  int collapsing = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 p0 = point(), p1 = point(), p2 = point();
    const Polygon face{{{p0, 0, 0}, {p1, 0, 0}, {p2, 0, 0}}, 0};
    const auto plane = supporting_plane(face);
    const double d0 = plane ? plane->distance(p0) : 0.0;
    if (d0 == 0.0) continue;
    const Vec3 across = p0 - plane->n * std::copysign(1.0, d0), beside = point();
    const Polygon neighbour{{{p0, 0, 0}, {across, 0, 0}, {beside, 0, 0}}, 1};
    if (classify(neighbour, *plane, kEps) != Side::Spanning) continue;
    const double d1 = plane->distance(across);
    collapsing += lerp(p0, across, d0 / (d0 - d1)) == p0;
    const auto r = split(neighbour, *plane, kEps);
    double parts = r.dropped_area;
    for (const auto& part : {r.front, r.back}) {
      if (!part) continue;
      parts += area(*part);
      for (std::size_t i = 0; i < part->verts.size(); ++i)
        ASSERT_GT(length(part->verts[i].p - part->verts[(i + 1) % part->verts.size()].p), kEps) << trial;
    }
    ASSERT_NEAR(parts, area(neighbour), 1e-12 * area(neighbour)) << trial;
  }
  EXPECT_GT(collapsing, 0);
}

namespace {

// The VmFlags line of the mapping in /proc/self/smaps that holds `address` ("hg" among them: the
// mapping was advised into huge pages), whatever the system's huge page settings; empty when the
// kernel reports none.
std::optional<std::string> mapping_flags(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t begin = 0, end = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &begin, &end) == 2 && line.find(':') > line.find(' ')) {
      inside = begin <= a && a < end;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line.substr(8) + " ";
    }
  }
  return std::nullopt;
}

bool advised(const std::string& flags) { return flags.find(" hg ") != std::string::npos; }

}  // namespace

// Arrays of kHugePageBytes or more are advised into huge pages; smaller mapped ones are not.
TEST(PageAllocator, AdvisesLargeArraysIntoHugePages) {
  if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) GTEST_SKIP() << "no transparent huge pages";
  PageVector<double> large(2 * kHugePageBytes / sizeof(double), 1.0);
  const auto large_flags = mapping_flags(large.data());
  if (!large_flags) GTEST_SKIP() << "the kernel reports no VmFlags";
  EXPECT_TRUE(advised(*large_flags)) << *large_flags;
  PageVector<double> small(kPageAllocationBytes / sizeof(double), 1.0);
  const auto small_flags = mapping_flags(small.data());
  ASSERT_TRUE(small_flags.has_value());
  EXPECT_FALSE(advised(*small_flags)) << *small_flags;
}
