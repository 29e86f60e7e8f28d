// random-disjoint: n small triangles that do not touch, one per cell of an m x m x m grid over the
// unit cube (m = ceil(cbrt(n)); cells filled in x-fastest order), each strictly inside its cell.
// Sizes are comparable and nothing crosses: de Berg's uncluttered scenes ("Linear size binary space
// partitions for uncluttered scenes", Algorithmica 28, 2000), the common case of the theory, where a
// good BSP has linear size. A heuristic that splits much here is wasting cuts.
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

// A triangle thinner than this (area over the squared cell size) is redrawn: the scene is meant to
// be uncluttered, not to test slivers (near-degenerate does that).
constexpr double kMinAreaFraction = 0.02;
constexpr int kMaxDraws = 64;

std::size_t grid_size(std::size_t n) {
  auto m = static_cast<std::size_t>(std::cbrt(static_cast<double>(n)));
  while (m * m * m < n) ++m;
  return std::max<std::size_t>(m, 1);
}

Polygon triangle_in_cell(std::size_t i, std::size_t m, double fill, std::uint64_t seed) {
  Rng rng(stream_seed(seed, i));
  const double h = 1.0 / static_cast<double>(m);
  const Vec3 lo{static_cast<double>(i % m) * h, static_cast<double>((i / m) % m) * h,
                static_cast<double>(i / (m * m)) * h};
  // Vertices inside the centred sub-box of side fill * h: strictly inside the cell.
  const double margin = 0.5 * (1 - fill) * h, span = fill * h;
  auto point = [&] {
    return lo + Vec3{margin + span * rng.uniform(), margin + span * rng.uniform(), margin + span * rng.uniform()};
  };
  Polygon t;
  for (int draw = 0; draw < kMaxDraws; ++draw) {
    t = triangle(point(), point(), point());
    if (area(t) >= kMinAreaFraction * h * h) break;
  }
  return t;
}

std::vector<Polygon> make(const ParamSet& p) {
  const std::size_t n = count_of(p), m = grid_size(n);
  const double fill = p.real("fill");
  const std::uint64_t seed = seed_of(p);
  return generate_items(n, [&](std::size_t i, std::vector<Polygon>& out) {
    out.push_back(triangle_in_cell(i, m, fill, seed));
  });
}

}  // namespace

GeneratorInfo random_disjoint_generator() {
  return {"random-disjoint",
          "uncluttered scene of small disjoint triangles, one per grid cell: a good BSP needs almost no splits",
          "exactly n triangles",
          {n_param(1000, "number of triangles"), seed_param(),
           {"fill", ParamSpec::Kind::Real,
            "side of the centred sub-box of its grid cell that holds a triangle's vertices, as a fraction of the cell",
            0.8, 0.05, 0.99, {}}},
          make,
          true};
}

}  // namespace bsp
