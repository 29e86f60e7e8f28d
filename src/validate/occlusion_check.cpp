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
    // Hits outside the view volume (before the near plane, past the far one) are clipped away.
    std::vector<Hit> hits;
    for (const Hit& h : batch.of(r)) {
      const double z = dot(rays[r].dir * h.t, look);
      if (z >= view.near && z <= view.far) hits.push_back(h);
    }
    if (hits.empty()) continue;
    ++out.rays_hitting;
    const Hit& first = hits.front();
    seen[first.fragment] = true;
    bool ok = in_set[first.fragment];
    for (std::size_t k = 1; k < hits.size() && !ok; ++k)
      ok = in_set[hits[k].fragment] && scene.tie_reason(rays[r], first, hits[k]) != TieReason::None;
    if (ok) continue;
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
