#include "validate/ray_shoot_check.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "tree/ray_shoot.h"

namespace bsp {

namespace {

template <class H>
std::string describe(const std::optional<H>& h) {
  return h ? "fragment " + std::to_string(h->fragment) + " at t=" + std::to_string(h->t) : "no hit";
}

}  // namespace

HitVerdict judge_first_hits(const std::optional<RayHit>& bsp, const std::optional<Hit>& embree, const Ray& ray,
                            const EmbreeScene& scene) {
  const auto same = [](const std::optional<RayHit>& a, const std::optional<Hit>& b) {
    return a.has_value() == b.has_value() && (!a || a->fragment == b->fragment);
  };
  if (same(bsp, embree)) return HitVerdict::Agree;
  const std::optional<Hit> truth = scene.first_hit_exhaustive(ray);
  if (same(bsp, truth)) return HitVerdict::AgreeExhaustive;
  if (!bsp || !truth) return HitVerdict::Mismatch;
  const std::optional<Hit> claimed = scene.hit(ray, bsp->fragment);
  if (!claimed) return HitVerdict::Mismatch;
  switch (scene.tie_reason(ray, *claimed, *truth)) {
    case TieReason::Coplanar: return HitVerdict::TieCoplanar;
    case TieReason::Edge: return HitVerdict::TieEdge;
    case TieReason::Boundary: return HitVerdict::TieBoundary;
    case TieReason::None: break;
  }
  return HitVerdict::Mismatch;
}

RayShootCheck check_ray_shooting(const Tree& tree, const EmbreeScene& embree, std::span<const Ray> rays) {
  RayShootCheck out;
  for (const Ray& ray : rays) {
    const std::optional<Hit> expected = embree.first_hit(ray);
    const std::optional<RayHit> got = shoot_ray(tree, ray).hit;
    ++out.rays;
    out.hits += expected.has_value();
    const HitVerdict verdict = judge_first_hits(got, expected, ray, embree);
    out.exhaustive += verdict != HitVerdict::Agree;
    switch (verdict) {
      case HitVerdict::Agree: case HitVerdict::AgreeExhaustive: break;
      case HitVerdict::TieCoplanar: ++out.ties_coplanar; break;
      case HitVerdict::TieEdge: ++out.ties_edge; break;
      case HitVerdict::TieBoundary: ++out.ties_boundary; break;
      case HitVerdict::Mismatch:
        if (out.mismatches++ < RayShootCheck::kMaxReported)
          out.first_problems.push_back("ray shooting found " + describe(got) + ", Embree " + describe(expected));
        break;
    }
  }
  return out;
}

RayShootCheck check_ray_shooting(const Tree& tree, const ValidationSettings& settings) {
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  const EmbreeScene embree(fragments, tree.tol.plane_eps);
  std::vector<Ray> rays;
  for (const Vec3& eye : validation_eyes(tree.bounds, settings.views)) {
    const std::vector<Ray> more = validation_rays(fragments, tree.bounds, eye, settings);
    rays.insert(rays.end(), more.begin(), more.end());
  }
  return check_ray_shooting(tree, embree, rays);
}

nlohmann::json to_json(const RayShootCheck& c) {
  return {{"rays", c.rays},
          {"hits", c.hits},
          {"exhaustive", c.exhaustive},
          {"ties", c.ties()},
          {"ties_coplanar", c.ties_coplanar},
          {"ties_edge", c.ties_edge},
          {"ties_boundary", c.ties_boundary},
          {"mismatches", c.mismatches},
          {"first_problems", c.first_problems}};
}

}  // namespace bsp
