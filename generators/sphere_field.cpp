// sphere-field: closed tessellated spheres of varied resolution, one per cell of an m x m x m grid
// over the unit cube (m = ceil(cbrt(s)) for s spheres), each strictly inside its cell, so no two
// overlap. Sphere i is a geodesic icosphere of frequency f_i (each icosahedron face cut into f_i^2
// triangles, vertices pushed onto the sphere): f_i runs through 1, 2, ..., K, 1, 2, ... and the
// frequencies are then shuffled over the spheres, so coarse and fine spheres are mixed everywhere.
//
// What it shows: many closed convex objects. Each sphere alone needs no split at all (every face has
// the whole sphere behind it), so a good BSP stays near n fragments; the few planes between spheres
// are free cuts, and a heuristic that picks sphere faces as splitters across the field splits
// neighbours. Icosphere vertices need only +, *, / and sqrt, so they are the same everywhere.
#include <array>
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr double kRadiusMin = 0.3, kRadiusMax = 0.9;  // radius as a fraction of half the cell side
constexpr std::uint64_t kShuffleStream = 0x5f1e1d;

// The regular icosahedron: vertices (0, ±1, ±φ) and their cyclic permutations; faces counter-clockwise
// seen from outside.
const double kPhi = (1 + std::sqrt(5.0)) / 2;
const std::array<Vec3, 12> kIcoVerts = {{{-1, kPhi, 0}, {1, kPhi, 0}, {-1, -kPhi, 0}, {1, -kPhi, 0},
                                         {0, -1, kPhi}, {0, 1, kPhi}, {0, -1, -kPhi}, {0, 1, -kPhi},
                                         {kPhi, 0, -1}, {kPhi, 0, 1}, {-kPhi, 0, -1}, {-kPhi, 0, 1}}};
constexpr std::array<std::array<int, 3>, 20> kIcoFaces = {{{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                                          {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                          {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                                          {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}}};

std::size_t frequency_of(std::size_t i, std::size_t max_frequency) { return 1 + i % max_frequency; }

// Largest s >= 1 whose spheres' triangles (20 f_i^2 each) stay within n.
std::size_t sphere_count(std::size_t n, std::size_t max_frequency) {
  std::size_t s = 1, total = 20;
  while (true) {
    const std::size_t f = frequency_of(s, max_frequency);
    if (total + 20 * f * f > n) return s;
    total += 20 * f * f;
    ++s;
  }
}

std::vector<std::size_t> shuffled_frequencies(std::size_t s, std::size_t max_frequency, std::uint64_t seed) {
  std::vector<std::size_t> f(s);
  for (std::size_t i = 0; i < s; ++i) f[i] = frequency_of(i, max_frequency);
  Rng rng(stream_seed(seed, kShuffleStream));
  for (std::size_t i = s; i > 1; --i) std::swap(f[i - 1], f[rng.below(i)]);  // Fisher-Yates
  return f;
}

void icosphere(const Vec3& centre, double radius, std::size_t k, std::vector<Polygon>& out) {
  const double kk = static_cast<double>(k);
  for (const auto& face : kIcoFaces) {
    const Vec3 &a = kIcoVerts[face[0]], &b = kIcoVerts[face[1]], &c = kIcoVerts[face[2]];
    auto point = [&](std::size_t i, std::size_t j) -> Vertex {
      const double bi = static_cast<double>(i), cj = static_cast<double>(j);
      const Vec3 p = a * (kk - bi - cj) + b * bi + c * cj;
      return {centre + p * (radius / length(p)), bi / kk, cj / kk};
    };
    for (std::size_t j = 0; j < k; ++j)
      for (std::size_t i = 0; i + j < k; ++i) {
        out.push_back({{point(i, j), point(i + 1, j), point(i, j + 1)}, 0});
        if (i + j + 1 < k) out.push_back({{point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)}, 0});
      }
  }
}

void sphere(std::size_t i, std::size_t m, std::size_t frequency, std::uint64_t seed, std::vector<Polygon>& out) {
  Rng rng(stream_seed(seed, i));
  const double h = 1.0 / static_cast<double>(m);
  const Vec3 lo{static_cast<double>(i % m) * h, static_cast<double>((i / m) % m) * h,
                static_cast<double>(i / (m * m)) * h};
  const double r = 0.5 * h * rng.uniform(kRadiusMin, kRadiusMax);
  const Vec3 centre = lo + Vec3{r + (h - 2 * r) * rng.uniform(), r + (h - 2 * r) * rng.uniform(),
                                r + (h - 2 * r) * rng.uniform()};
  icosphere(centre, r, frequency, out);
}

std::vector<Polygon> make(const ParamSet& p) {
  const auto max_frequency = static_cast<std::size_t>(p.integer("max_frequency"));
  const std::uint64_t seed = seed_of(p);
  const std::size_t s = sphere_count(count_of(p), max_frequency);
  auto m = static_cast<std::size_t>(std::cbrt(static_cast<double>(s)));
  while (m * m * m < s) ++m;
  const auto frequencies = shuffled_frequencies(s, max_frequency, seed);
  return generate_items(s, [&](std::size_t i, std::vector<Polygon>& out) {
    sphere(i, std::max<std::size_t>(m, 1), frequencies[i], seed, out);
  });
}

}  // namespace

GeneratorInfo sphere_field_generator() {
  return {"sphere-field",
          "non-overlapping closed spheres of mixed resolution: convex objects that need no splits, only cuts "
          "between them",
          "sum over spheres i < s of 20 f_i^2 triangles, f_i = 1 + (i mod max_frequency) (then shuffled over the "
          "spheres), s the largest count (at least 1) keeping the sum within n",
          {n_param(20000, "largest number of triangles"), seed_param(),
           {"max_frequency", ParamSpec::Kind::Integer,
            "finest sphere: frequencies cycle 1..max_frequency (a frequency-f sphere has 20 f^2 triangles)", 8, 1, 200,
            {}}},
          make,
          true};
}

}  // namespace bsp
