// Closed solids for solid trees and set operations: every surface is closed and its faces are
// counter-clockwise seen from outside. Shared vertices are computed once, so neighbouring faces
// meet in bit-identical points. Each solid is placed by its centre (x, y, z) and size (scale), so a
// pair that overlaps is two scenes with different placements (README: `bspbench merge`).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "catalog.h"
#include "common/rng.h"
#include "geometry/convex_loop.h"
#include "geometry/mesh_weld.h"
#include "geometry/polytope.h"
#include "shapes.h"

namespace bsp {

namespace {

// Local coordinates (the solid inside [-1, 1]^3, or [-2, 2]^3 for the polytope) to the scene: a
// rotation drawn from the seed (Shoemake's uniform random quaternion; seed 0 keeps the axes), the
// scale, then the centre. Each shared vertex is placed once, or from the same local point.
struct Placement {
  Vec3 centre;
  double scale;
  Vec3 rx{1, 0, 0}, ry{0, 1, 0}, rz{0, 0, 1};  // rows of the rotation
  Vec3 operator()(const Vec3& p) const { return centre + Vec3{dot(rx, p), dot(ry, p), dot(rz, p)} * scale; }
};

Placement placement(const ParamSet& p) {
  Placement place{{p.real("x"), p.real("y"), p.real("z")}, p.real("scale")};
  if (seed_of(p) == 0) return place;
  Rng rng(stream_seed(seed_of(p), 1));
  const double u1 = rng.uniform(), u2 = rng.uniform(0, 2 * std::numbers::pi), u3 = rng.uniform(0, 2 * std::numbers::pi);
  const double a = std::sqrt(1 - u1) * std::sin(u2), b = std::sqrt(1 - u1) * std::cos(u2);
  const double c = std::sqrt(u1) * std::sin(u3), w = std::sqrt(u1) * std::cos(u3);
  place.rx = {1 - 2 * (b * b + c * c), 2 * (a * b - c * w), 2 * (a * c + b * w)};
  place.ry = {2 * (a * b + c * w), 1 - 2 * (a * a + c * c), 2 * (b * c - a * w)};
  place.rz = {2 * (a * c - b * w), 2 * (b * c + a * w), 1 - 2 * (a * a + b * b)};
  return place;
}

std::vector<ParamSpec> solid_params(double default_n, std::string n_doc) {
  ParamSpec seed = seed_param();
  seed.doc = "random rotation about the centre (0: none)";
  return {n_param(default_n, std::move(n_doc)),
          seed,
          {"x", ParamSpec::Kind::Real, "centre, x", 0, -1e6, 1e6, {}},
          {"y", ParamSpec::Kind::Real, "centre, y", 0, -1e6, 1e6, {}},
          {"z", ParamSpec::Kind::Real, "centre, z", 0, -1e6, 1e6, {}},
          {"scale", ParamSpec::Kind::Real, "size: radius, or half the edge of a box", 1, 1e-6, 1e6, {}}};
}

std::size_t rounded_root(double x, std::size_t least) {
  return std::max(least, static_cast<std::size_t>(std::llround(std::sqrt(std::max(x, 0.0)))));
}

void number(std::vector<Polygon>& polys) {
  for (std::size_t i = 0; i < polys.size(); ++i) polys[i].source = static_cast<std::uint32_t>(i);
}

// A grid of vertices wrapped in u (and v when closed_v); quads split into two triangles.
std::vector<Polygon> wrapped_grid(const std::vector<Vec3>& grid, std::size_t nu, std::size_t nv) {
  std::vector<Polygon> out;
  const auto at = [&](std::size_t i, std::size_t j) { return grid[(j % nv) * nu + (i % nu)]; };
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t i = 0; i < nu; ++i) {
      out.push_back(triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1)));
      out.push_back(triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1)));
    }
  return out;
}

// UV sphere: s slices, m + 1 stacks; the stacks next to the poles are fans of triangles, the
// others quads split in two: 2 s m triangles.
std::vector<Polygon> make_sphere(const ParamSet& p) {
  const Placement place = placement(p);
  const double n = static_cast<double>(count_of(p));
  const std::size_t m = rounded_root(n / 4.0, 1), k = m + 1;
  const auto slices = std::max<std::size_t>(3, static_cast<std::size_t>(std::llround(n / (2.0 * static_cast<double>(m)))));
  const double pi = std::numbers::pi;
  std::vector<Vec3> ring;  // rings 1 .. k-1, each of `slices` vertices
  for (std::size_t j = 1; j < k; ++j)
    for (std::size_t i = 0; i < slices; ++i) {
      const double theta = pi * static_cast<double>(j) / static_cast<double>(k);
      const double phi = 2 * pi * static_cast<double>(i) / static_cast<double>(slices);
      ring.push_back(place({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)}));
    }
  const Vec3 north = place({0, 0, 1}), south = place({0, 0, -1});
  const auto at = [&](std::size_t j, std::size_t i) { return ring[(j - 1) * slices + i % slices]; };
  std::vector<Polygon> out;
  for (std::size_t i = 0; i < slices; ++i) out.push_back(triangle(north, at(1, i), at(1, i + 1)));
  for (std::size_t j = 1; j + 1 < k; ++j)
    for (std::size_t i = 0; i < slices; ++i) {
      out.push_back(triangle(at(j, i), at(j + 1, i), at(j + 1, i + 1)));
      out.push_back(triangle(at(j, i), at(j + 1, i + 1), at(j, i + 1)));
    }
  for (std::size_t i = 0; i < slices; ++i) out.push_back(triangle(south, at(k - 1, i + 1), at(k - 1, i)));
  number(out);
  return out;
}

std::vector<Polygon> make_torus(const ParamSet& p) {
  const Placement place = placement(p);
  const std::size_t nv = rounded_root(static_cast<double>(count_of(p)) / 4.0, 3), nu = 2 * nv;
  const double pi = std::numbers::pi, minor = 0.35;
  std::vector<Vec3> grid;
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t i = 0; i < nu; ++i) {
      const double a = 2 * pi * static_cast<double>(i) / static_cast<double>(nu);
      const double b = 2 * pi * static_cast<double>(j) / static_cast<double>(nv);
      const double r = 1 + minor * std::cos(b);
      grid.push_back(place({r * std::cos(a), r * std::sin(a), minor * std::sin(b)}));
    }
  std::vector<Polygon> out = wrapped_grid(grid, nu, nv);
  number(out);
  return out;
}

// The six faces of the cube [-h, h]^3 (local coordinates), each split into k x k quads whose
// corners come from one integer lattice, so that faces meeting at an edge share its points.
void add_box(std::vector<Polygon>& out, const Placement& place, double h, std::size_t k, bool inward) {
  const auto lattice = [&](const std::size_t g[3]) {
    const auto c = [&](std::size_t i) { return h * (2.0 * static_cast<double>(i) / static_cast<double>(k) - 1.0); };
    return place({c(g[0]), c(g[1]), c(g[2])});
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const bool positive : {false, true}) {
      // (u, v) counter-clockwise seen from outside: u x v points away from the cube.
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      if (positive == inward) std::swap(u, v);
      for (std::size_t a = 0; a < k; ++a)
        for (std::size_t b = 0; b < k; ++b) {
          Polygon poly;
          const std::size_t du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int corner = 0; corner < 4; ++corner) {
            std::size_t g[3];
            g[axis] = positive ? k : 0;
            g[u] = a + du[corner];
            g[v] = b + dv[corner];
            poly.verts.push_back({lattice(g), static_cast<double>(du[corner]), static_cast<double>(dv[corner])});
          }
          out.push_back(std::move(poly));
        }
    }
}

std::vector<Polygon> make_box(const ParamSet& p) {
  const Placement place = placement(p);
  std::vector<Polygon> out;
  add_box(out, place, 1.0, rounded_root(static_cast<double>(count_of(p)) / 6.0, 1), false);
  number(out);
  return out;
}

std::vector<Polygon> make_hollow_box(const ParamSet& p) {
  const Placement place = placement(p);
  const std::size_t k = rounded_root(static_cast<double>(count_of(p)) / 12.0, 1);
  std::vector<Polygon> out;
  add_box(out, place, 1.0, k, false);
  add_box(out, place, 0.5, k, true);
  number(out);
  return out;
}

std::vector<Polygon> make_cylinder(const ParamSet& p) {
  const Placement place = placement(p);
  const std::size_t s = std::max<std::size_t>(3, count_of(p) / 3);
  const double pi = std::numbers::pi;
  std::vector<Vec3> bottom, top;
  for (std::size_t i = 0; i < s; ++i) {
    const double a = 2 * pi * static_cast<double>(i) / static_cast<double>(s);
    bottom.push_back(place({std::cos(a), std::sin(a), -1}));
    top.push_back(place({std::cos(a), std::sin(a), 1}));
  }
  const Vec3 cb = place({0, 0, -1}), ct = place({0, 0, 1});
  std::vector<Polygon> out;
  for (std::size_t i = 0; i < s; ++i) {
    const std::size_t j = (i + 1) % s;
    out.push_back(quad(bottom[i], bottom[j], top[j], top[i]));
    out.push_back(triangle(ct, top[i], top[j]));
    out.push_back(triangle(cb, bottom[j], bottom[i]));
  }
  number(out);
  return out;
}

// The cube [-2, 2]^3 (in units of scale) cut by n planes tangent to the unit sphere, with
// normals uniform on the sphere; faces welded so that neighbours share their corners.
std::vector<Polygon> make_convex_polytope(const ParamSet& p) {
  const Placement place = placement(p);
  Rng rng(stream_seed(seed_of(p), 0));
  ConvexPolytope cell = ConvexPolytope::box({{-2, -2, -2}, {2, 2, 2}});
  for (std::size_t i = 0; i < count_of(p); ++i) {
    const double z = rng.uniform(-1, 1), a = rng.uniform(0, 2 * std::numbers::pi), r = std::sqrt(1 - z * z);
    const Vec3 n{r * std::cos(a), r * std::sin(a), z};
    cell = cell.clipped({-n, 1.0}, 1e-12);
  }
  LoopPool faces;
  for (std::size_t f = 0; f < cell.face_count(); ++f) faces.add(cell.face(f));
  const IndexedMesh mesh = weld_loops(faces, 1e-9).mesh;
  std::vector<Polygon> out;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    Polygon poly;
    for (std::uint32_t c = mesh.start[f]; c < mesh.start[f + 1]; ++c) poly.verts.push_back({place(mesh.vertices[mesh.corners[c]])});
    out.push_back(std::move(poly));
  }
  number(out);
  return out;
}

// Menger sponge of the given level: unit voxels of a 3^level grid, kept unless at least two of
// their base-3 digits at some level are 1; a face is emitted between a kept voxel and a removed or
// outside one.
std::vector<Polygon> make_menger(const ParamSet& p) {
  const Placement place = placement(p);
  const auto level = static_cast<int>(p.integer("level"));
  int side = 1;
  for (int i = 0; i < level; ++i) side *= 3;
  const auto kept = [&](int x, int y, int z) {
    if (x < 0 || y < 0 || z < 0 || x >= side || y >= side || z >= side) return false;
    for (; x || y || z; x /= 3, y /= 3, z /= 3)
      if ((x % 3 == 1) + (y % 3 == 1) + (z % 3 == 1) >= 2) return false;
    return true;
  };
  const double unit = 2.0 / side;
  const auto corner = [&](int x, int y, int z) { return place({-1 + x * unit, -1 + y * unit, -1 + z * unit}); };
  std::vector<Polygon> out;
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      for (int z = 0; z < side; ++z) {
        if (!kept(x, y, z)) continue;
        if (!kept(x - 1, y, z)) out.push_back(quad(corner(x, y, z), corner(x, y, z + 1), corner(x, y + 1, z + 1), corner(x, y + 1, z)));
        if (!kept(x + 1, y, z)) out.push_back(quad(corner(x + 1, y, z), corner(x + 1, y + 1, z), corner(x + 1, y + 1, z + 1), corner(x + 1, y, z + 1)));
        if (!kept(x, y - 1, z)) out.push_back(quad(corner(x, y, z), corner(x + 1, y, z), corner(x + 1, y, z + 1), corner(x, y, z + 1)));
        if (!kept(x, y + 1, z)) out.push_back(quad(corner(x, y + 1, z), corner(x, y + 1, z + 1), corner(x + 1, y + 1, z + 1), corner(x + 1, y + 1, z)));
        if (!kept(x, y, z - 1)) out.push_back(quad(corner(x, y, z), corner(x, y + 1, z), corner(x + 1, y + 1, z), corner(x + 1, y, z)));
        if (!kept(x, y, z + 1)) out.push_back(quad(corner(x, y, z + 1), corner(x + 1, y, z + 1), corner(x + 1, y + 1, z + 1), corner(x, y + 1, z + 1)));
      }
  number(out);
  return out;
}

GeneratorInfo solid(std::string name, std::string purpose, std::string rule, std::vector<ParamSpec> params,
                    std::function<std::vector<Polygon>(const ParamSet&)> make) {
  GeneratorInfo g{std::move(name), std::move(purpose), std::move(rule), std::move(params), std::move(make)};
  g.closed_solid = true;
  return g;
}

}  // namespace

std::vector<GeneratorInfo> solid_generators() {
  std::vector<ParamSpec> menger = solid_params(1, "unused: the level sets the count");
  menger.push_back({"level", ParamSpec::Kind::Integer, "recursion level", 1, 1, 3, {}});
  // Each plane clips the whole polytope: quadratic in n.
  std::vector<ParamSpec> polytope = solid_params(100, "number of random tangent planes (at most 5000)");
  polytope.front().max = 5000;
  return {
      solid("sphere", "closed UV sphere: a convex solid whose autopartition is a chain",
            "2sm triangles, m = max(1, round(sqrt(n/4))), s = max(3, round(n/(2m))) (s slices, m + 1 stacks): "
            "exactly n when 2m divides n (10^3 gives 992, 10^4 exactly 10^4, 10^5 99,856)",
            solid_params(1000, "number of triangles (see the count rule)"), make_sphere),
      solid("torus", "closed torus (tube radius 0.35 of the ring's): a solid with a hole",
            "4k^2 triangles, k = max(3, round(sqrt(n/4))) (2k around the ring, k around the tube)",
            solid_params(1000, "number of triangles (rounded to 4k^2)"), make_torus),
      solid("box", "axis-aligned cube, each face split into k x k quads: coplanar faces",
            "6k^2 quads, k = max(1, round(sqrt(n/6)))", solid_params(6, "number of quads (rounded to 6k^2)"), make_box),
      solid("hollow-box", "cube with a cube-shaped cavity (inner faces point into the cavity)",
            "12k^2 quads, k = max(1, round(sqrt(n/12)))", solid_params(12, "number of quads (rounded to 12k^2)"),
            make_hollow_box),
      solid("cylinder", "closed cylinder: s side quads and two fans of s triangles",
            "3s polygons, s = max(3, floor(n/3))", solid_params(96, "number of polygons (rounded down to 3s)"),
            make_cylinder),
      solid("convex-polytope", "random convex polytope: the cube [-2,2]^3 cut by n planes tangent to the unit sphere",
            "at most n + 6 faces (planes that cut nothing off leave no face)", polytope, make_convex_polytope),
      solid("menger-sponge", "Menger sponge: non-convex, tunnels through it, many coplanar faces",
            "one unit quad per face between a kept voxel and a removed one: 72 at level 1, 1,056 at 2, 18,048 at 3 (n unused)",
            menger, make_menger),
  };
}

}  // namespace bsp
