#include "validate/ray_shoot_check.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "metrics/ray_shoot.h"

namespace bsp {

namespace {

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = dot(ab, ab);
  const double s = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + ab * s));
}

// How far the ray's line passes from the polygon's boundary: both projected along the ray onto
// the plane through its origin perpendicular to it, where the line becomes the origin point.
double line_to_boundary(const Polygon& poly, const Ray& ray) {
  const Vec3 u = normalize(ray.dir);
  const auto project = [&](const Vec3& p) { return (p - ray.origin) - u * dot(p - ray.origin, u); };
  double best = 1e300;
  for (std::size_t i = 0, k = poly.verts.size(); i < k; ++i)
    best = std::min(best, distance_to_segment({}, project(poly.verts[i].p), project(poly.verts[(i + 1) % k].p)));
  return best;
}

std::string describe(const std::optional<Hit>& h) {
  return h ? "fragment " + std::to_string(h->fragment) + " at t=" + std::to_string(h->t) : "no hit";
}

}  // namespace

HitVerdict judge_first_hits(const std::optional<Hit>& bsp, const std::optional<Hit>& embree, const Ray& ray,
                            std::span<const Polygon> fragments, double tie) {
  if (!bsp && !embree) return HitVerdict::Agree;
  if (bsp && embree && bsp->fragment == embree->fragment) return HitVerdict::Agree;
  if (bsp && embree && std::abs(bsp->t - embree->t) * length(ray.dir) <= tie) return HitVerdict::Tie;
  const Hit& nearer = !embree || (bsp && bsp->t < embree->t) ? *bsp : *embree;
  return line_to_boundary(fragments[nearer.fragment], ray) <= tie ? HitVerdict::Grazing : HitVerdict::Mismatch;
}

RayShootCheck check_ray_shooting(const Tree& tree, const EmbreeScene& embree, std::span<const Ray> rays) {
  RayShootCheck out;
  const double tie = embree.tie_tolerance();
  for (const Ray& ray : rays) {
    const std::optional<Hit> expected = embree.first_hit(ray);
    const std::optional<Hit> got = shoot_ray(tree, ray).hit;
    ++out.rays;
    out.hits += expected.has_value();
    switch (judge_first_hits(got, expected, ray, tree.fragments, tie)) {
      case HitVerdict::Agree: break;
      case HitVerdict::Tie: ++out.ties; break;
      case HitVerdict::Grazing: ++out.grazing; break;
      case HitVerdict::Mismatch:
        if (out.mismatches++ < RayShootCheck::kMaxReported)
          out.first_problems.push_back("ray shooting found " + describe(got) + ", Embree " + describe(expected));
        break;
    }
  }
  return out;
}

RayShootCheck check_ray_shooting(const Tree& tree, const ValidationSettings& settings) {
  const EmbreeScene embree(tree.fragments, settings.tie_relative);
  std::vector<Ray> rays;
  for (const Vec3& eye : validation_eyes(tree.bounds, settings.views)) {
    const std::vector<Ray> more = validation_rays(tree.fragments, tree.bounds, eye, settings);
    rays.insert(rays.end(), more.begin(), more.end());
  }
  return check_ray_shooting(tree, embree, rays);
}

nlohmann::json to_json(const RayShootCheck& c) {
  return {{"rays", c.rays},   {"hits", c.hits},           {"ties", c.ties},
          {"grazing", c.grazing}, {"mismatches", c.mismatches}, {"first_problems", c.first_problems}};
}

}  // namespace bsp
