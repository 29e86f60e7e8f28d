// coplanar-heavy: n polygons (alternately rectangles and triangles) on only `planes` planes through
// the unit cube, half of them facing each way. Even-numbered planes are axis-aligned (their polygons
// share the plane bit for bit), odd-numbered ones have random orientations (their polygons agree
// with the plane only up to rounding, within the tolerance). Polygon i lies on plane i mod planes at
// a random spot, randomly rotated within it; polygons on one plane overlap freely.
//
// What it shows: whether a heuristic and the builder treat coplanar polygons as one split (all of
// them stored at one node, both orientations) rather than as many; a tree of depth about `planes`
// is possible, and every extra cut along a shared plane is waste.
#include <cmath>
#include <utility>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr double kMinExtent = 0.3;  // least polygon half-size, as a fraction of `size`
constexpr double kMinTriangle = 0.05;  // least triangle area (before halving), as a fraction of size^2
constexpr std::uint64_t kPlaneStream = 0x91a4e5;

// An oriented plane through `point` with an orthonormal frame (u, v, normal = cross(u, v)).
struct Frame {
  Vec3 point, u, v, normal;
  bool axis_aligned = false;
  int axis = 0;
};

// Uniform directions by rejection from the cube (square): only sqrt, the same everywhere.
Vec3 random_unit(Rng& rng) {
  while (true) {
    const Vec3 d{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const double l2 = dot(d, d);
    if (l2 > 1e-4 && l2 <= 1) return d / std::sqrt(l2);
  }
}

std::pair<double, double> random_unit_2d(Rng& rng) {
  while (true) {
    const double x = rng.uniform(-1, 1), y = rng.uniform(-1, 1), l2 = x * x + y * y;
    if (l2 > 1e-4 && l2 <= 1) return {x / std::sqrt(l2), y / std::sqrt(l2)};
  }
}

Frame make_frame(std::size_t index, std::uint64_t seed) {
  Rng rng(stream_seed(stream_seed(seed, kPlaneStream), index));
  Frame f;
  f.point = {rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7)};
  f.axis_aligned = index % 2 == 0;
  if (f.axis_aligned) {
    f.axis = static_cast<int>((index / 2) % 3);
    const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    f.normal = axes[f.axis];
    f.u = axes[(f.axis + 1) % 3];
    f.v = axes[(f.axis + 2) % 3];
    return f;
  }
  f.normal = random_unit(rng);
  const Vec3 e = std::abs(f.normal.x) < 0.5 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  f.u = normalize(cross(e, f.normal));
  f.v = cross(f.normal, f.u);
  return f;
}

// The point of the plane at in-plane coordinates (a, b) from the frame's projection of `centre`;
// on axis-aligned planes the plane's coordinate is copied exactly.
Vec3 on_plane(const Frame& f, const Vec3& centre, double a, double b) {
  Vec3 p = centre + f.u * a + f.v * b;
  if (f.axis_aligned) {
    double* c[3] = {&p.x, &p.y, &p.z};
    *c[f.axis] = f.point[f.axis];
  }
  return p;
}

Polygon polygon_on(const Frame& f, std::size_t i, double size, std::uint64_t seed) {
  Rng rng(stream_seed(seed, i));
  const Vec3 q{rng.uniform(), rng.uniform(), rng.uniform()};
  const Vec3 centre = q - f.normal * dot(f.normal, q - f.point);
  Polygon poly;
  if (i % 2 == 0) {  // rectangle rotated by a random in-plane direction (dx, dy)
    const double a = size * rng.uniform(kMinExtent, 1), b = size * rng.uniform(kMinExtent, 1);
    const auto [dx, dy] = random_unit_2d(rng);
    // Init-captures: clang before 16 cannot capture a structured binding (the fuzz build uses clang 14).
    auto corner = [&, dx = dx, dy = dy](double s, double t) {
      return on_plane(f, centre, s * a * dx - t * b * dy, s * a * dy + t * b * dx);
    };
    poly = quad(corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1));
  } else {  // triangle: three random in-plane points, not too thin, ordered counter-clockwise
    double a[3] = {}, b[3] = {}, twice_area = 0;
    while (std::abs(twice_area) < kMinTriangle * size * size) {
      for (int k = 0; k < 3; ++k) a[k] = size * rng.uniform(-1, 1), b[k] = size * rng.uniform(-1, 1);
      twice_area = (a[1] - a[0]) * (b[2] - b[0]) - (a[2] - a[0]) * (b[1] - b[0]);
    }
    if (twice_area < 0) std::swap(a[1], a[2]), std::swap(b[1], b[2]);
    poly = triangle(on_plane(f, centre, a[0], b[0]), on_plane(f, centre, a[1], b[1]), on_plane(f, centre, a[2], b[2]));
  }
  return rng.uniform() < 0.5 ? poly : flipped(std::move(poly));
}

std::vector<Polygon> make(const ParamSet& p) {
  const auto planes = static_cast<std::size_t>(p.integer("planes"));
  const std::uint64_t seed = seed_of(p);
  const double size = p.real("size");
  std::vector<Frame> frames;
  for (std::size_t k = 0; k < planes; ++k) frames.push_back(make_frame(k, seed));
  return generate_items(count_of(p), [&](std::size_t i, std::vector<Polygon>& out) {
    out.push_back(polygon_on(frames[i % planes], i, size, seed));
  });
}

}  // namespace

GeneratorInfo coplanar_heavy_generator() {
  return {"coplanar-heavy",
          "many polygons on a few planes, facing both ways: coplanar polygons must share one node, not cost splits",
          "exactly n polygons (rectangles at even indices, triangles at odd), polygon i on plane i mod planes",
          {n_param(1000, "number of polygons"), seed_param(),
           {"planes", ParamSpec::Kind::Integer, "number of distinct planes (even ones axis-aligned)", 6, 1, 1e6, {}},
           {"size", ParamSpec::Kind::Real, "largest polygon half-size", 0.15, 1e-4, 10, {}}},
          make};
}

}  // namespace bsp
