// saddle-grid: the quadratic lower-bound construction. The hyperbolic paraboloid z = xy contains the
// lines x = a (points (a, y, a y)) and y = b (points (x, b, x b)). Take k lines of each family over
// [-1, 1]^2: every line of one family crosses every line of the other. Lift the first family by
// delta so the families miss each other, and thicken each line into a thin planar strip. Chazelle
// used this configuration for the Omega(n^2) lower bound on convex decompositions (SIAM J. Comput.
// 13, 1984), and Paterson and Yao for the Omega(n^2) lower bound on BSPs of n segments or polygons
// in R^3 ("Efficient binary space partitions for hidden-surface removal and solid modeling",
// Discrete Comput. Geom. 5, 1990): every BSP of it has Omega(n^2) fragments. The plane of a strip of
// one family cuts nearly every strip of the other, so splits grow as k^2 whatever the heuristic.
//
// Geometry: strip x = a_i is the planar quad {(a_i + s, y, a_i y + delta) : |s| <= w, |y| <= 1};
// strip y = b_j is {(x, b_j + t, x b_j) : |x| <= 1, |t| <= w}. Where they overlap in x and y, their
// heights differ by delta + a_i t - s b_j >= delta - 2w > 0 (|a_i|, |b_j| < 1), so with delta = 3w
// no two strips meet. Line positions are evenly spaced with a random jitter of up to a quarter of
// the spacing (the seed).
#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr double kHalfWidthOfSpacing = 0.1;  // strip half-width w, as a fraction of the line spacing
constexpr double kLiftOfHalfWidth = 3.0;     // delta / w; must exceed 2 for the families to miss
constexpr double kJitter = 0.25;             // largest shift of a line, as a fraction of the spacing

std::vector<Polygon> make(const ParamSet& p) {
  const std::size_t k = std::max<std::size_t>(1, count_of(p) / 2);
  const std::uint64_t seed = seed_of(p);
  const double spacing = 2.0 / static_cast<double>(k);
  const double w = kHalfWidthOfSpacing * spacing, delta = kLiftOfHalfWidth * w;
  return generate_items(2 * k, [&](std::size_t item, std::vector<Polygon>& out) {
    Rng rng(stream_seed(seed, item));
    const std::size_t i = item % k;
    const double c = -1 + (static_cast<double>(i) + 0.5 + kJitter * rng.uniform(-1, 1)) * spacing;
    if (item < k)  // x = c, lifted by delta; faces +z-ish
      out.push_back(quad({c - w, -1, -c + delta}, {c + w, -1, -c + delta}, {c + w, 1, c + delta},
                         {c - w, 1, c + delta}));
    else  // y = c
      out.push_back(quad({-1, c - w, -c}, {1, c - w, c}, {1, c + w, c}, {-1, c + w, -c}));
  });
}

}  // namespace

GeneratorInfo saddle_grid_generator() {
  return {"saddle-grid",
          "Paterson-Yao lower bound: two families of thin strips on z = xy where every BSP has Omega(n^2) fragments",
          "2 k strips (quads), k = max(1, floor(n / 2)) per family",
          {n_param(200, "number of strips (rounded down to even, at least 2)"), seed_param()},
          make};
}

}  // namespace bsp
