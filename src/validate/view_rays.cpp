#include "validate/view_rays.h"

#include <array>
#include <cmath>

#include "common/rng.h"

namespace bsp {

namespace {

// Fixed seed of the eye stream: changing it changes every eye of every validation.
constexpr std::uint64_t kEyeSeed = 0x5eed0e7e;
// Outside eyes cycle through these distances from the box centre, in box diagonals.
constexpr std::array<double, 3> kOutsideDiagonals = {1.5, 2.5, 4.0};
// Inside eyes stay within this fraction of the box around its centre, so they are not on its faces.
constexpr double kInsideSpan = 0.8;
// A flat box axis is widened to this fraction of the diagonal, so inside eyes of a planar scene
// are not in its plane.
constexpr double kMinExtent = 0.05;
// A sample point closer to the eye than this fraction of the diagonal is where the eye sits on the
// fragment: it gives no direction to aim at.
constexpr double kMinAimDistance = 1e-9;

double safe_diagonal(const Box& box) {
  const double d = box.diagonal();
  return d > 0.0 ? d : 1.0;
}

// Uniform on the unit sphere (Archimedes: z uniform, longitude uniform).
Vec3 sphere_point(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0);
  const double phi = rng.uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 inside_point(const Box& box, Rng& rng) {
  const double diag = safe_diagonal(box);
  const Vec3 c = box.empty() ? Vec3{} : box.center();
  const Vec3 size = box.empty() ? Vec3{} : box.size();
  std::array<double, 3> p{};
  for (int a = 0; a < 3; ++a) {
    const double extent = std::max(size[a], kMinExtent * diag);
    p[a] = c[a] + (rng.uniform() - 0.5) * kInsideSpan * extent;
  }
  return {p[0], p[1], p[2]};
}

struct Frame {
  Vec3 forward, right, up;
};

Frame frame_towards(const Vec3& forward) {
  const Vec3 helper = std::abs(forward.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 right = normalize(cross(forward, helper));
  return {forward, right, cross(right, forward)};
}

void add_ray(std::vector<Ray>& rays, const Vec3& eye, const Vec3& dir) {
  const double len = length(dir);
  if (len > 0.0 && std::isfinite(len)) rays.push_back({eye, dir / len});
}

void fragment_rays(std::span<const Polygon> fragments, const Vec3& eye, double pull, double min_dist,
                   std::vector<Ray>& rays) {
  for (const auto& f : fragments) {
    if (f.verts.size() < 3) continue;
    const Vec3 c = centroid(f);
    const auto aim = [&](const Vec3& p) {
      if (length(p - eye) > min_dist) add_ray(rays, eye, p - eye);
    };
    aim(c);
    for (const auto& v : f.verts) aim(lerp(v.p, c, pull));
  }
}

// Pixel centres of a grid x grid image covering the box's projection; false when some box corner
// is not in front of the eye (then no single image covers the box).
bool projected_grid_rays(const Box& box, const Vec3& eye, int grid, std::vector<Ray>& rays) {
  const Frame f = frame_towards(normalize(box.center() - eye));
  const double near = 1e-6 * safe_diagonal(box);
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{(k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z};
    const Vec3 d = corner - eye;
    const double z = dot(d, f.forward);
    if (!(z > near)) return false;
    const double x = dot(d, f.right) / z, y = dot(d, f.up) / z;
    lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
  }
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const double x = lo_x + (hi_x - lo_x) * (i + 0.5) / grid;
      const double y = lo_y + (hi_y - lo_y) * (j + 0.5) / grid;
      add_ray(rays, eye, f.forward + f.right * x + f.up * y);
    }
  return true;
}

void cube_map_rays(const Vec3& eye, int grid, std::vector<Ray>& rays) {
  const std::array<Vec3, 3> axes = {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  for (int a = 0; a < 3; ++a)
    for (double sign : {1.0, -1.0}) {
      const Vec3 face = axes[a] * sign, e1 = axes[(a + 1) % 3], e2 = axes[(a + 2) % 3];
      for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j) {
          const double u = -1.0 + 2.0 * (i + 0.5) / grid, v = -1.0 + 2.0 * (j + 0.5) / grid;
          add_ray(rays, eye, face + e1 * u + e2 * v);
        }
    }
}

}  // namespace

std::vector<Vec3> validation_eyes(const Box& box, int views) {
  std::vector<Vec3> eyes;
  const double diag = safe_diagonal(box);
  const Vec3 c = box.empty() ? Vec3{} : box.center();
  for (int k = 0; k < views; ++k) {
    Rng rng(stream_seed(kEyeSeed, static_cast<std::uint64_t>(k)));
    if (k % 2 == 0)
      eyes.push_back(c + sphere_point(rng) * (kOutsideDiagonals[(k / 2) % kOutsideDiagonals.size()] * diag));
    else
      eyes.push_back(inside_point(box, rng));
  }
  return eyes;
}

std::vector<Ray> validation_rays(std::span<const Polygon> fragments, const Box& box, const Vec3& eye,
                                 const ValidationSettings& settings) {
  std::vector<Ray> rays;
  const double min_dist = kMinAimDistance * safe_diagonal(box);
  fragment_rays(fragments, eye, settings.vertex_pull, min_dist, rays);
  if (box.empty() || !projected_grid_rays(box, eye, settings.grid, rays)) cube_map_rays(eye, settings.cube_grid, rays);
  return rays;
}

}  // namespace bsp
