#pragma once
// One view of occlusion culling, shared by `bspbench occlude` and the sweep's occlude jobs: the
// beam-traced potentially visible set (cull/occlusion.h) with its cost, frustum culling alone on the
// same view, and the Embree proof (validate/occlusion_check.h) with how many fragments rays see.
#include <nlohmann/json.hpp>

#include "cull/occlusion.h"
#include "validate/occlusion_check.h"

namespace bsp::experiments {

// {eye, look, emitted, frustum_culled, seen_by_embree, emitted_per_seen, emitted_per_frustum_culled,
// missed_fragments, missed_rays, rays, rays_hitting, problems, cpu_seconds, frustum_cpu_seconds,
// nodes_visited, frustum_nodes_visited, and the OcclusionCounters}. all_ok becomes false when the
// proof finds a miss.
nlohmann::json occlusion_view(const Tree& tree, const Occluder& occluder, const Frustum& view,
                              const OcclusionCheckSettings& check, bool& all_ok);

}  // namespace bsp::experiments
