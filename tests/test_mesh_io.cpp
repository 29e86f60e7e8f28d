// Meshes from files: every format (OBJ, OFF, PLY, STL) read from small files written here, convex
// planar faces kept whole, non-convex and non-planar faces ear-clipped without losing area,
// zero-area and repeated-vertex faces dropped and counted, the CLI's one-line warning about it,
// OBJ output that reads back exactly, and the real CGAL sample meshes (skipped when not fetched).
#include <gtest/gtest.h>

#include "cli_runner.h"
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <vector>

#include "catalog.h"
#include "io/mesh_reader.h"
#include "io/polygon_cleanup.h"
#include "mesh_scenes.h"

using namespace bsp;
namespace fs = std::filesystem;

namespace {

Polygon poly(std::initializer_list<Vec3> points) {
  Polygon p;
  for (const auto& x : points) p.verts.push_back({x, 0, 0});
  return p;
}

double total_area(const std::vector<Polygon>& polys) {
  double a = 0;
  for (const auto& p : polys) a += area(p);
  return a;
}

// Even-odd point-in-polygon in the xy plane.
bool inside_xy(const Polygon& outline, const Vec3& q) {
  bool in = false;
  const auto& v = outline.verts;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i].p.y > q.y) != (v[j].p.y > q.y) &&
        q.x < (v[j].p.x - v[i].p.x) * (q.y - v[i].p.y) / (v[j].p.y - v[i].p.y) + v[i].p.x)
      in = !in;
  return in;
}

// The faces every polygonal format gets, in this order (1-based indices into kPoints):
//  a convex quad (kept), an L-shaped hexagon (non-convex: 4 triangles, area 3), a twisted quad
//  (non-planar: 2 triangles), a pentagram (self-crossing: triangulated), a collinear triangle
//  (zero area: dropped), a face repeating a vertex (dropped), a rectangle with a T-junction vertex
//  on one edge (convex and planar: kept with its 5 vertices).
const std::vector<Vec3> kPoints = {
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},                                  // 1-4 quad
    {0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {1, 1, 1}, {1, 2, 1}, {0, 2, 1},            // 5-10 L
    {0, 0, 2}, {1, 0, 2}, {1, 1, 2.5}, {0, 1, 2},                                // 11-14 twisted
    {0, 1, 3}, {0.588, -0.809, 3}, {-0.951, 0.309, 3}, {0.951, 0.309, 3}, {-0.588, -0.809, 3},  // 15-19 star
    {0, 0, 4}, {1, 0, 4}, {2, 0, 4},                                             // 20-22 collinear
    {0, 0, 5}, {2, 0, 5}, {2, 1, 5}, {0, 1, 5}, {1, 0, 5},                       // 23-27 T rectangle
};
const std::vector<std::vector<int>> kFaces = {
    {1, 2, 3, 4}, {5, 6, 7, 8, 9, 10}, {11, 12, 13, 14}, {15, 16, 17, 18, 19}, {20, 21, 22}, {1, 2, 1},
    {23, 27, 24, 25, 26},
};

class MeshFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = "bspbench_mesh_" + std::string(info->name()) + "_" + std::to_string(::getpid());
    dir_ = fs::temp_directory_path() / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& content) const {
    std::ofstream(dir_ / name) << content;
    return dir_ / name;
  }

  std::string obj() const {
    std::ostringstream s;
    for (const auto& p : kPoints) s << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const auto& f : kFaces) {
      s << "f";
      for (int i : f) s << " " << i;
      s << "\n";
    }
    return s.str();
  }

  // The vertex and face lines OFF and ASCII PLY share: "x y z", then "k i0 i1 ..." 0-based.
  std::string vertices_and_faces() const {
    std::ostringstream s;
    for (const auto& p : kPoints) s << p.x << " " << p.y << " " << p.z << "\n";
    for (const auto& f : kFaces) {
      s << f.size();
      for (int i : f) s << " " << i - 1;
      s << "\n";
    }
    return s.str();
  }

  std::string off() const {
    std::ostringstream s;
    s << "OFF\n" << kPoints.size() << " " << kFaces.size() << " 0\n" << vertices_and_faces();
    return s.str();
  }

  std::string ply() const {
    std::ostringstream s;
    s << "ply\nformat ascii 1.0\nelement vertex " << kPoints.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << kFaces.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n"
      << vertices_and_faces();
    return s.str();
  }

  fs::path dir_;
};

// What every polygonal format must give for kFaces.
void expect_cleaned(const Scene& s) {
  EXPECT_EQ(s.load.faces_read, 7u);
  EXPECT_EQ(s.load.triangulated, 3u);
  EXPECT_EQ(s.load.dropped_degenerate, 1u);
  EXPECT_EQ(s.load.dropped_duplicate_vertex, 1u);
  std::vector<Polygon> quads, l_shape, twisted, star, t_rect;
  for (const auto& p : s.polygons) {
    EXPECT_TRUE(is_convex_planar(p, 1e-9)) << "a polygon the build cannot take";
    const double z = p.verts[0].p.z;
    (z == 0 ? quads : z == 1 ? l_shape : z < 3 ? twisted : z == 3 ? star : t_rect).push_back(p);
  }
  ASSERT_EQ(quads.size(), 1u);
  EXPECT_EQ(quads[0].verts.size(), 4u) << "a convex quad must stay a quad";
  EXPECT_EQ(l_shape.size(), 4u);
  EXPECT_NEAR(total_area(l_shape), 3.0, 1e-12);
  for (const auto& t : l_shape) EXPECT_EQ(t.verts.size(), 3u);
  EXPECT_EQ(twisted.size(), 2u);
  EXPECT_GE(star.size(), 1u);
  ASSERT_EQ(t_rect.size(), 1u);
  EXPECT_EQ(t_rect[0].verts.size(), 5u) << "a T-junction vertex does not make a rectangle non-convex";
}

}  // namespace

TEST_F(MeshFiles, ObjFacesAreCleaned) { expect_cleaned(read_mesh(write("faces.obj", obj()).string())); }
TEST_F(MeshFiles, OffFacesAreCleaned) { expect_cleaned(read_mesh(write("faces.off", off()).string())); }
TEST_F(MeshFiles, PlyFacesAreCleaned) { expect_cleaned(read_mesh(write("faces.ply", ply()).string())); }

TEST_F(MeshFiles, StlTrianglesAreReadAndDegenerateOnesDropped) {
  auto facet = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    std::ostringstream s;
    s << "facet normal 0 0 1\nouter loop\n";
    for (const Vec3& p : {a, b, c}) s << "vertex " << p.x << " " << p.y << " " << p.z << "\n";
    s << "endloop\nendfacet\n";
    return s.str();
  };
  // Two good triangles, a collinear one and one repeating a point.
  const std::string stl = "solid t\n" + facet({0, 0, 0}, {1, 0, 0}, {0, 1, 0}) +
                          facet({1, 0, 0}, {1, 1, 0}, {0, 1, 0}) + facet({0, 0, 1}, {1, 0, 1}, {2, 0, 1}) +
                          facet({0, 0, 2}, {1, 0, 2}, {0, 0, 2}) + "endsolid t\n";
  const Scene s = read_mesh(write("tris.stl", stl).string());
  EXPECT_EQ(s.load.faces_read, 4u);
  EXPECT_EQ(s.polygons.size(), 2u);
  EXPECT_EQ(s.load.dropped_degenerate + s.load.dropped_duplicate_vertex, 2u);
  EXPECT_NEAR(total_area(s.polygons), 1.0, 1e-12);
}

// The CGAL reader quiets std::cerr by swapping its buffer; two sweep jobs reading meshes at once
// restored each other's buffers, one of them destroyed, and the sweep crashed (SweepCli's cached-mesh
// suite on 2 threads). Many threads reading at once must leave std::cerr's buffer as it was.
TEST_F(MeshFiles, ConcurrentReadsLeaveStdCerrAsItWas) {
  const std::string path = write("faces.off", off()).string();
  std::streambuf* const before = std::cerr.rdbuf();
  std::vector<std::thread> readers;
  std::vector<std::size_t> counts(8);
  for (std::size_t t = 0; t < counts.size(); ++t)
    readers.emplace_back([&, t] {
      for (int i = 0; i < 50; ++i) counts[t] = read_mesh(path).polygons.size();
    });
  for (auto& r : readers) r.join();
  EXPECT_EQ(std::cerr.rdbuf(), before);
  for (std::size_t c : counts) EXPECT_EQ(c, counts[0]);
  EXPECT_GT(counts[0], 0u);
}

TEST(EarClipping, NonConvexPolygonKeepsItsAreaAndStaysInsideItsOutline) {
  // A comb: base [0, 9] x [0, 1] with five teeth [2t, 2t + 1] x [1, 3], counter-clockwise; area 19.
  const Polygon comb = poly({{0, 0, 0}, {9, 0, 0}, {9, 3, 0}, {8, 3, 0}, {8, 1, 0}, {7, 1, 0}, {7, 3, 0},
                             {6, 3, 0}, {6, 1, 0}, {5, 1, 0}, {5, 3, 0}, {4, 3, 0}, {4, 1, 0}, {3, 1, 0},
                             {3, 3, 0}, {2, 3, 0}, {2, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}});
  const double outline_area = area(comb);
  ASSERT_DOUBLE_EQ(outline_area, 19.0);
  ASSERT_FALSE(is_convex_planar(comb, 1e-12));
  const auto tris = ear_clip(comb, 1e-12);
  EXPECT_NEAR(total_area(tris), outline_area, 1e-9);
  // At most k - 2 triangles: clipping can leave vertices in line with their neighbours, which
  // are then removed without a triangle.
  EXPECT_LE(tris.size(), comb.verts.size() - 2);
  for (const auto& t : tris) {
    EXPECT_GT(dot(newell_normal(t), newell_normal(comb)), 0) << "a triangle flipped";
    EXPECT_TRUE(inside_xy(comb, centroid(t))) << "a triangle outside the outline";
  }
}

TEST(EarClipping, VerticesInLineWithTheirNeighboursAddNoTriangles) {
  const Polygon square =
      poly({{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 0.5, 0}, {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}, {0, 0.5, 0}});
  const auto tris = ear_clip(square, 1e-12);
  EXPECT_EQ(tris.size(), 2u);
  EXPECT_NEAR(total_area(tris), 1.0, 1e-12);
}

TEST(ConvexPlanar, TellsConvexPlanarFromNonConvexNonPlanarAndSelfCrossing) {
  EXPECT_TRUE(is_convex_planar(poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}), 1e-9));
  EXPECT_TRUE(is_convex_planar(poly({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}), 1e-9));
  EXPECT_FALSE(is_convex_planar(poly({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}}), 1e-9));
  EXPECT_FALSE(is_convex_planar(poly({{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {2, 2, 0}, {0, 2, 0}}), 1e-9));
  EXPECT_FALSE(is_convex_planar(poly({{0, 1, 0}, {0.588, -0.809, 0}, {-0.951, 0.309, 0}, {0.951, 0.309, 0},
                                      {-0.588, -0.809, 0}}),
                                1e-9))
      << "a pentagram turns left at every vertex but winds twice";
}

namespace {

using CliRun = bsp::testing::CliResult;
using bsp::testing::slurp;

CliRun run_cli(const std::string& args, const fs::path& dir) { return bsp::testing::run_bspbench(args, dir); }

}  // namespace

TEST_F(MeshFiles, CliWarnsInOneLineAboutWhatLoadingChanged) {
  const fs::path in = write("faces.obj", obj());
  const CliRun r = run_cli("generate --input " + in.string() + " --out " + (dir_ / "copy.obj").string(), dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("3 triangulated"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 dropped (zero area)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 dropped (repeated vertex)"), std::string::npos) << r.err;
  const CliRun clean = run_cli("generate --scene city --n 60 --out " + (dir_ / "city.obj").string(), dir_);
  EXPECT_TRUE(clean.err.empty()) << "a generated scene needs no warning: " << clean.err;
}

TEST_F(MeshFiles, GeneratedObjReadsBackWithTheSameCoordinates) {
  for (const std::string scene : {"architecture", "sphere-field", "near-degenerate"}) {
    const fs::path out = dir_ / (scene + ".obj");
    const CliRun r = run_cli("generate --scene " + scene + " --n 300 --seed 5 --json --out " + out.string(), dir_);
    ASSERT_EQ(r.code, 0) << r.err;
    const Scene made = make_scene(scene, {{"n", "300"}, {"seed", "5"}});
    EXPECT_EQ(nlohmann::json::parse(r.out)["hash"], content_hash(made)) << scene;
    const Scene back = read_mesh(out.string());
    // near-degenerate's sub-tolerance polygons are dropped on reading; the others come back whole.
    ASSERT_EQ(back.polygons.size() + back.load.dropped_degenerate, made.polygons.size()) << scene;
    std::size_t j = 0;
    for (const auto& p : made.polygons) {
      if (j == back.polygons.size() || back.polygons[j].verts.size() != p.verts.size()) continue;
      bool same = true;
      for (std::size_t k = 0; k < p.verts.size(); ++k) same &= back.polygons[j].verts[k].p == p.verts[k].p;
      j += same;
    }
    EXPECT_EQ(j, back.polygons.size()) << scene << ": coordinates changed on the way through OBJ";
  }
}

TEST(MeshScenes, CgalSampleMeshesLoadAsConvexPlanarPolygons) {
  if (available_meshes().empty())
    GTEST_SKIP() << "no meshes in " << mesh_cache_dir() << ": run generators/fetch_meshes.sh (needs apt-get)";
  for (const std::string name : {"bunny", "armadillo", "elephant", "dragon"}) {
    const Scene s = make_scene("mesh:" + name, {});
    EXPECT_EQ(s.name, "mesh:" + name);
    EXPECT_GT(s.polygons.size(), 1000u) << name;
    EXPECT_EQ(s.polygons.size() + s.load.dropped_degenerate + s.load.dropped_duplicate_vertex, s.load.faces_read)
        << name << ": all-triangle meshes need no triangulation";
    const Box b = bounds(s);
    EXPECT_TRUE(is_finite(b.lo) && is_finite(b.hi) && b.diagonal() > 0) << name;
    EXPECT_EQ(content_hash(s), content_hash(make_scene("mesh:" + name, {}))) << name;
  }
}

TEST(MeshScenes, ScenesJsonListsGeneratorsAndFetchedMeshes) {
  const fs::path dir = fs::temp_directory_path() / ("bspbench_scenes_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const CliRun r = run_cli("scenes --json", dir);
  fs::remove_all(dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto list = nlohmann::json::parse(r.out);
  std::size_t generated = 0, meshes = 0;
  for (const auto& s : list) {
    if (s["kind"] == "generator") {
      ++generated;
      EXPECT_FALSE(s["count"].get<std::string>().empty()) << s["name"];
      for (const auto& p : s["params"]) EXPECT_TRUE(p.contains("default") && p.contains("doc")) << s["name"];
    } else {
      ++meshes;
      EXPECT_EQ(s["name"].get<std::string>().rfind("mesh:", 0), 0u) << s["name"];
    }
  }
  EXPECT_EQ(generated, generators().size());
  EXPECT_EQ(meshes, available_meshes().size());
}
