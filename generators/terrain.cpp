// terrain: a height field over the unit square, an m x m grid of cells split into two triangles each
// (the diagonal alternating like a checkerboard), heights from a few octaves of value noise. With
// overhangs > 0, thin rock shelves (boxes) hover just above the ground, so the scene stops being a
// height field: several surfaces lie above one ground point, as under a cliff overhang.
//
// What it shows: a large connected mesh of nearly coplanar neighbours (smooth hills meet at tiny
// dihedral angles), where any plane through one triangle grazes many others; and, with overhangs,
// whether a heuristic still handles the few polygons that break the 2.5D structure.
//
// Heights use only +, *, and comparisons on doubles (no libm), so they are the same everywhere.
#include <algorithm>
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr int kOctaves = 5;
constexpr double kBaseFrequency = 4.0;  // noise lattice cells across the terrain at the first octave
constexpr double kShelfMin = 0.03, kShelfMax = 0.08;  // shelf side
constexpr double kShelfThickness = 0.01;
constexpr double kShelfClearance = 0.02;  // gap between a shelf and the highest ground below it

enum Stream : std::uint64_t { kNoise = 1, kShelves };

// Value noise: random values on an integer lattice, blended with smoothstep.
double lattice(std::uint64_t stream, std::int64_t ix, std::int64_t iy) {
  const auto key = (static_cast<std::uint64_t>(iy) << 32) ^ static_cast<std::uint64_t>(ix);
  return static_cast<double>(splitmix64(stream_seed(stream, key)) >> 11) * 0x1.0p-53;
}

double value_noise(std::uint64_t stream, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  const double a = lattice(stream, ix, iy), b = lattice(stream, ix + 1, iy);
  const double c = lattice(stream, ix, iy + 1), d = lattice(stream, ix + 1, iy + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

// In [-relief / 2, relief / 2].
double height(std::uint64_t seed, double relief, double x, double y) {
  double sum = 0, amplitude = 1, total = 0, frequency = kBaseFrequency;
  for (int o = 0; o < kOctaves; ++o) {
    sum += amplitude * (value_noise(stream_seed(stream_seed(seed, kNoise), o), x * frequency, y * frequency) - 0.5);
    total += amplitude;
    amplitude *= 0.5;
    frequency *= 2;
  }
  return relief * sum / total;
}

struct Field {
  std::size_t m;
  std::vector<double> z;  // (m + 1)^2 vertex heights, row-major in y
  double at(std::size_t i, std::size_t j) const { return z[j * (m + 1) + i]; }
  Vertex vertex(std::size_t i, std::size_t j) const {
    const double side = static_cast<double>(m);
    const double x = static_cast<double>(i) / side, y = static_cast<double>(j) / side;
    return {{x, y, at(i, j)}, x, y};
  }
};

void cell(const Field& f, std::size_t c, std::vector<Polygon>& out) {
  const std::size_t i = c % f.m, j = c / f.m;
  const Vertex a = f.vertex(i, j), b = f.vertex(i + 1, j), cc = f.vertex(i + 1, j + 1), d = f.vertex(i, j + 1);
  if ((i + j) % 2 == 0) {
    out.push_back({{a, b, cc}, 0});
    out.push_back({{a, cc, d}, 0});
  } else {
    out.push_back({{a, b, d}, 0});
    out.push_back({{b, cc, d}, 0});
  }
}

// A thin box whose bottom clears every ground vertex of the cells under it (the ground is linear
// between its vertices, so it clears the ground).
void shelf(const Field& f, std::size_t k, std::uint64_t seed, std::vector<Polygon>& out) {
  Rng rng(stream_seed(stream_seed(seed, kShelves), k));
  const double w = rng.uniform(kShelfMin, kShelfMax), d = rng.uniform(kShelfMin, kShelfMax);
  const double x0 = rng.uniform(0, 1 - w), y0 = rng.uniform(0, 1 - d);
  const double m = static_cast<double>(f.m);
  const auto i0 = static_cast<std::size_t>(std::floor(x0 * m)), j0 = static_cast<std::size_t>(std::floor(y0 * m));
  const auto i1 = std::min(f.m, static_cast<std::size_t>(std::ceil((x0 + w) * m)));
  const auto j1 = std::min(f.m, static_cast<std::size_t>(std::ceil((y0 + d) * m)));
  double top = -1e300;
  for (std::size_t j = j0; j <= j1; ++j)
    for (std::size_t i = i0; i <= i1; ++i) top = std::max(top, f.at(i, j));
  const Vec3 lo{x0, y0, top + kShelfClearance};
  const Vec3 x{w, 0, 0}, y{0, d, 0}, up{0, 0, kShelfThickness};
  out.push_back(parallelogram(lo, y, x));             // bottom, faces -z: the overhang
  out.push_back(parallelogram(lo + up, x, y));        // top
  out.push_back(parallelogram(lo, x, up));            // faces -y
  out.push_back(parallelogram(lo + x, y, up));        // faces +x
  out.push_back(parallelogram(lo + x + y, x * -1, up));  // faces +y
  out.push_back(parallelogram(lo + y, y * -1, up));      // faces -x
}

std::vector<Polygon> make(const ParamSet& p) {
  Field f;
  f.m = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(static_cast<double>(count_of(p)) / 2)));
  const std::uint64_t seed = seed_of(p);
  const double relief = p.real("relief");
  const std::size_t side = f.m + 1;
  f.z.resize(side * side);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < side * side; ++k)
    f.z[k] = height(seed, relief, static_cast<double>(k % side) / static_cast<double>(f.m),
                    static_cast<double>(k / side) / static_cast<double>(f.m));
  const std::size_t cells = f.m * f.m, shelves = static_cast<std::size_t>(p.integer("overhangs"));
  return generate_items(cells + shelves, [&](std::size_t item, std::vector<Polygon>& out) {
    if (item < cells) cell(f, item, out);
    else shelf(f, item - cells, seed, out);
  });
}

}  // namespace

GeneratorInfo terrain_generator() {
  return {"terrain",
          "height-field triangle mesh of smooth hills, optionally with overhanging shelves that break the 2.5D "
          "structure",
          "2 m^2 + 6 * overhangs polygons, m = max(1, floor(sqrt(n / 2))): two triangles per grid cell, six quads "
          "per shelf",
          {n_param(2000, "largest number of ground triangles (rounded down to 2 m^2)"), seed_param(),
           {"relief", ParamSpec::Kind::Real, "height range of the ground; the terrain spans the unit square", 0.3,
            0.0, 100, {}},
           {"overhangs", ParamSpec::Kind::Integer,
            "number of shelves hovering over the ground (0: a pure height field)", 0, 0, 1e6, {}}},
          make,
          true};
}

}  // namespace bsp
