// random-triangles: n triangles with uniformly random centres in the unit cube [0,1]^3 and vertices
// scattered up to `size` from the centre. At the default size and n beyond a few hundred they
// intersect each other: a soup, the hard general case where every heuristic must split.
#include <cmath>

#include "catalog.h"
#include "common/rng.h"

namespace bsp {

namespace {

std::vector<Polygon> make(const ParamSet& p) {
  const auto n = static_cast<std::size_t>(p.integer("n"));
  const auto seed = static_cast<std::uint64_t>(p.integer("seed"));
  const double size = p.real("size");
  std::vector<Polygon> out(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    Rng rng(stream_seed(seed, i));
    const Vec3 c{rng.uniform(), rng.uniform(), rng.uniform()};
    Polygon& t = out[i];
    t.source = static_cast<std::uint32_t>(i);
    const double uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (const auto& tex : uv) {
      const Vec3 offset{rng.uniform(-size, size), rng.uniform(-size, size), rng.uniform(-size, size)};
      t.verts.push_back({c + offset, tex[0], tex[1]});
    }
  }
  return out;
}

}  // namespace

GeneratorInfo random_triangles_generator() {
  return {"random-triangles",
          "intersecting triangle soup in the unit cube: the general case where every plane splits something",
          "exactly n triangles",
          {n_param(1000, "number of triangles"), seed_param(),
           {"size", ParamSpec::Kind::Real, "largest vertex offset from a triangle's centre, per axis", 0.1, 1e-6, 10, {}}},
          make};
}

}  // namespace bsp
