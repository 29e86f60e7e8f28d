#include "validate/occlusion_check.h"

#include <algorithm>

#include "validate/embree_scene.h"

namespace bsp {

namespace {

std::vector<Ray> occlusion_rays(const Tree& tree, const Frustum& view, const OcclusionCheckSettings& s) {
  std::vector<Ray> rays;
  const std::array<Vec3, 8> c = view.corners();
  for (int i = 0; i < s.grid; ++i)
    for (int j = 0; j < s.grid; ++j) {
      const double u = (i + 0.5) / s.grid, v = (j + 0.5) / s.grid;
      rays.push_back({view.eye, c[0] + (c[2] - c[0]) * u + (c[1] - c[0]) * v - view.eye});
    }
  for (const FragmentView f : tree.fragments) {
    Vec3 centre;
    for (const Vec3& p : f.p) centre += p;
    centre = centre / static_cast<double>(f.size());
    const auto aim = [&](const Vec3& p) {
      if (view.contains(p, 0)) rays.push_back({view.eye, p - view.eye});
    };
    aim(centre);
    for (const Vec3& p : f.p) aim(p + (centre - p) * s.vertex_pull);
  }
  return rays;
}

// The hits of a ray inside the view volume (what lies before the near plane or past the far one is
// clipped away), nearest first.
std::vector<Hit> in_view(std::span<const Hit> hits, const Ray& ray, const Frustum& view, const Vec3& look) {
  std::vector<Hit> out;
  for (const Hit& h : hits) {
    const double z = dot(ray.dir * h.t, look);
    if (z >= view.near && z <= view.far) out.push_back(h);
  }
  return out;
}

// Every fragment's exact hit by the ray, without Embree, sorted as all_hits sorts: for the rays whose
// Embree candidates cannot be trusted.
std::vector<Hit> exhaustive_hits(const EmbreeScene& scene, const Ray& ray) {
  std::vector<Hit> out;
  for (std::uint32_t f = 0; f < scene.fragment_count(); ++f)
    if (const auto h = scene.hit(ray, f)) out.push_back(*h);
  std::sort(out.begin(), out.end(), [](const Hit& a, const Hit& b) { return a.t != b.t ? a.t < b.t : a.fragment < b.fragment; });
  return out;
}

// Whether the first hit, or one tied with it, is in the set.
bool first_in_set(const EmbreeScene& scene, const Ray& ray, const std::vector<Hit>& hits, const std::vector<bool>& in_set) {
  const Hit& first = hits.front();
  bool ok = in_set[first.fragment];
  for (std::size_t k = 1; k < hits.size() && !ok; ++k)
    ok = in_set[hits[k].fragment] && scene.tie_reason(ray, first, hits[k]) != TieReason::None;
  return ok;
}

}  // namespace

OcclusionCheck check_occlusion(const Tree& tree, const Frustum& view, std::span<const std::uint32_t> emitted,
                               const OcclusionCheckSettings& settings) {
  OcclusionCheck out;
  if (tree.fragments.empty()) return out;
  const EmbreeScene scene(tree.fragments.to_polygons(), tree.tol.plane_eps);
  std::vector<bool> in_set(tree.fragments.size(), false), seen(tree.fragments.size(), false),
      missed(tree.fragments.size(), false);
  for (const std::uint32_t f : emitted) in_set[f] = true;
  const std::vector<Ray> rays = occlusion_rays(tree, view, settings);
  out.rays = rays.size();
  HitBatch batch;
  scene.all_hits(rays, batch);
  const Vec3 look = normalize(view.look);
  for (std::size_t r = 0; r < rays.size(); ++r) {
    std::vector<Hit> hits = in_view(batch.of(r), rays[r], view, look);
    if (hits.empty()) continue;
    if (first_in_set(scene, rays[r], hits, in_set)) {
      ++out.rays_hitting;
      seen[hits.front().fragment] = true;
      continue;
    }
    // Embree proposes candidates in floats, and a ray meeting a fragment's plane at a grazing angle
    // may lose its candidate (embree_scene.h): before a ray counts as missed, its hits are
    // recomputed exactly against every fragment.
    ++out.rays_rechecked;
    hits = in_view(exhaustive_hits(scene, rays[r]), rays[r], view, look);
    if (hits.empty()) continue;
    ++out.rays_hitting;
    const Hit& first = hits.front();
    seen[first.fragment] = true;
    if (first_in_set(scene, rays[r], hits, in_set)) continue;
    ++out.missed_rays;
    if (!missed[first.fragment] && out.first_problems.size() < 10)
      out.first_problems.push_back("fragment " + std::to_string(first.fragment) + " is seen by ray " +
                                   std::to_string(r) + " but was culled");
    missed[first.fragment] = true;
  }
  out.seen_fragments = static_cast<std::uint64_t>(std::count(seen.begin(), seen.end(), true));
  out.missed_fragments = static_cast<std::uint64_t>(std::count(missed.begin(), missed.end(), true));
  return out;
}

}  // namespace bsp
