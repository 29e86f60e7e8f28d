// city: a g x g grid of lots on the ground plane z = 0. Each lot is one ground tile (a quad facing
// up) with a building standing on it: an axis-aligned box with a random footprint inside the lot
// (leaving a street margin) and a random height, as four walls and a flat roof. Heights follow a
// skyline-like skew: most buildings are low, a few are towers.
//
// What it shows: a 2.5D scene with large occluders; the ground tiles are all coplanar and every
// building face is axis-aligned, so a few well-chosen planes separate whole blocks, while tall
// towers make the back-to-front order depend strongly on the eye.
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr double kLot = 1.0;          // lot side
constexpr double kStreet = 0.15;      // least margin between a building and its lot's edge
constexpr double kMinFootprint = 0.3;  // least building side, as a fraction of the usable lot
constexpr double kMinHeight = 0.2;

void lot(std::size_t i, std::size_t g, double max_height, std::uint64_t seed, std::vector<Polygon>& out) {
  Rng rng(stream_seed(seed, i));
  const Vec3 corner{static_cast<double>(i % g) * kLot, static_cast<double>(i / g) * kLot, 0};
  out.push_back(parallelogram(corner, {kLot, 0, 0}, {0, kLot, 0}));
  const double usable = kLot - 2 * kStreet;
  const double w = usable * rng.uniform(kMinFootprint, 1.0), d = usable * rng.uniform(kMinFootprint, 1.0);
  const Vec3 lo = corner + Vec3{kStreet + (usable - w) * rng.uniform(), kStreet + (usable - d) * rng.uniform(), 0};
  // Cubing a uniform skews heights like a skyline: many low buildings, a few towers.
  const double u = rng.uniform(), h = kMinHeight + (max_height - kMinHeight) * u * u * u;
  const Vec3 x{w, 0, 0}, y{0, d, 0}, up{0, 0, h};
  out.push_back(parallelogram(lo, x, up));                  // faces -y
  out.push_back(parallelogram(lo + x, y, up));              // faces +x
  out.push_back(parallelogram(lo + x + y, x * -1, up));     // faces +y
  out.push_back(parallelogram(lo + y, y * -1, up));         // faces -x
  out.push_back(parallelogram(lo + up, x, y));              // roof, faces +z
}

std::vector<Polygon> make(const ParamSet& p) {
  const auto g = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(static_cast<double>(count_of(p)) / 6)));
  const double max_height = p.real("max_height");
  const std::uint64_t seed = seed_of(p);
  return generate_items(g * g, [&](std::size_t i, std::vector<Polygon>& out) { lot(i, g, max_height, seed, out); });
}

}  // namespace

GeneratorInfo city_generator() {
  return {"city",
          "extruded buildings of varied heights on a tiled ground plane: big axis-aligned occluders, 2.5D",
          "6 g^2 polygons, g = max(1, floor(sqrt(n / 6))): per lot one ground tile, four walls and a roof",
          {n_param(6000, "largest number of polygons (rounded down to 6 g^2)"), seed_param(),
           {"max_height", ParamSpec::Kind::Real, "tallest building, in lot sides (lots are 1 x 1)", 6.0, 0.5, 1000,
            {}}},
          make,
          true};
}

}  // namespace bsp
