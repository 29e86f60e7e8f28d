// cyclic-overlap: groups of three thin triangles ("sticks") in a pinwheel, each lying over the next
// where they cross and under the previous one, so no depth sort of whole polygons orders a group
// from above: a BSP must cut the cycle. Groups sit on a grid of unit cells, randomly rotated.
//
// Construction of one group, in its local frame: V_0, V_1, V_2 are an equilateral triangle of
// circumradius 0.3. Stick i runs along the line V_i -> V_{i+1}, from t = -0.25 to t = 1.25, at
// height z = h (1 - 2 s) where s in [0,1] is the position along the stick; it passes V_i at s = 1/6
// (z = +2h/3) and V_{i+1} at s = 5/6 (z = -2h/3). So at V_{i+1} stick i+1 lies 4h/3 above stick i:
// 1 over 0, 2 over 1, 0 over 2. Each stick is a triangle with its base (half-width w) at the start
// and its apex at the end; w is small against the stick length, so sticks never intersect.
#include <array>
#include <cmath>

#include "catalog.h"
#include "common/rng.h"

namespace bsp {

namespace {

constexpr double kRadius = 0.3;
constexpr double kHalfHeight = 0.06;
constexpr double kHalfWidth = 0.035;

// A random rotation: a uniformly random unit quaternion (Shoemake).
std::array<Vec3, 3> random_rotation(Rng& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform() * 2 * M_PI, u3 = rng.uniform() * 2 * M_PI;
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double w = a * std::sin(u2), x = a * std::cos(u2), y = b * std::sin(u3), z = b * std::cos(u3);
  return {Vec3{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
          Vec3{2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
          Vec3{2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
}

Vec3 rotate(const std::array<Vec3, 3>& r, const Vec3& v) { return {dot(r[0], v), dot(r[1], v), dot(r[2], v)}; }

void make_group(std::size_t g, std::size_t cells, std::uint64_t seed, Polygon* out) {
  Rng rng(stream_seed(seed, g));
  const auto rot = random_rotation(rng);
  const Vec3 cell{static_cast<double>(g % cells), static_cast<double>((g / cells) % cells),
                  static_cast<double>(g / (cells * cells))};
  const Vec3 origin = cell + Vec3{0.5, 0.5, 0.5};
  Vec3 v[3];
  for (int i = 0; i < 3; ++i) {
    const double angle = 2 * M_PI * i / 3;
    v[i] = {kRadius * std::cos(angle), kRadius * std::sin(angle), 0};
  }
  for (int i = 0; i < 3; ++i) {
    const Vec3 dir = v[(i + 1) % 3] - v[i];
    const Vec3 start = v[i] - dir * 0.25, end = v[i] + dir * 1.25;
    const Vec3 side = normalize(Vec3{-dir.y, dir.x, 0}) * kHalfWidth;
    const Vec3 up{0, 0, kHalfHeight};
    Polygon& t = out[i];
    t.source = static_cast<std::uint32_t>(3 * g + i);
    t.verts = {{origin + rotate(rot, start + side + up), 0, 0},
               {origin + rotate(rot, start - side + up), 1, 0},
               {origin + rotate(rot, end - up), 0.5, 1}};
  }
}

std::vector<Polygon> make(const ParamSet& p) {
  const auto groups = static_cast<std::size_t>(std::max<std::int64_t>(1, p.integer("n") / 3));
  const auto seed = static_cast<std::uint64_t>(p.integer("seed"));
  const auto cells = static_cast<std::size_t>(std::ceil(std::cbrt(static_cast<double>(groups)) - 1e-9));
  std::vector<Polygon> out(3 * groups);
#pragma omp parallel for schedule(static)
  for (std::size_t g = 0; g < groups; ++g) make_group(g, std::max<std::size_t>(cells, 1), seed, &out[3 * g]);
  return out;
}

}  // namespace

GeneratorInfo cyclic_overlap_generator() {
  return {"cyclic-overlap",
          "groups of three mutually overlapping sticks that no depth sort can order: a BSP must cut every cycle",
          "3 * max(1, floor(n / 3)) triangles: floor(n/3) groups of three",
          {n_param(300, "number of triangles (rounded down to a multiple of 3, at least 3)"), seed_param()},
          make,
          true};
}

}  // namespace bsp
