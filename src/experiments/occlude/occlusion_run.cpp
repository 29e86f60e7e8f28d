#include "experiments/occlude/occlusion_run.h"

#include "common/cpu_time.h"

namespace bsp::experiments {

nlohmann::json occlusion_view(const Tree& tree, const Occluder& occluder, const Frustum& view,
                        const OcclusionCheckSettings& check, bool& all_ok) {
  OcclusionCounters c;
  const double start = thread_cpu_seconds();
  const std::vector<std::uint32_t> out = occluder.visible(view, &c);
  const double seconds = thread_cpu_seconds() - start;
  const double frustum_start = thread_cpu_seconds();
  const TraversalCounters frustum = traverse_culled(tree, view, [](std::uint32_t) {});
  const double frustum_seconds = thread_cpu_seconds() - frustum_start;
  const OcclusionCheck proof = check_occlusion(tree, view, out, check);
  all_ok = all_ok && proof.ok();
  const auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
  return {{"eye", {view.eye.x, view.eye.y, view.eye.z}},
          {"look", {view.look.x, view.look.y, view.look.z}},
          {"emitted", out.size()},
          {"frustum_culled", frustum.fragments_emitted},
          {"seen_by_embree", proof.seen_fragments},
          {"emitted_per_seen", ratio(static_cast<double>(out.size()), static_cast<double>(proof.seen_fragments))},
          {"emitted_per_frustum_culled",
           ratio(static_cast<double>(out.size()), static_cast<double>(frustum.fragments_emitted))},
          {"missed_fragments", proof.missed_fragments},
          {"missed_rays", proof.missed_rays},
          {"rays", proof.rays},
          {"rays_hitting", proof.rays_hitting},
          {"rays_rechecked", proof.rays_rechecked},
          {"problems", proof.first_problems},
          {"cpu_seconds", seconds},
          {"frustum_cpu_seconds", frustum_seconds},
          {"nodes_visited", c.nodes_visited},
          {"frustum_nodes_visited", frustum.nodes_visited},
          {"subtrees_tested", c.subtrees_tested},
          {"subtrees_culled", c.subtrees_culled},
          {"fragments_tested", c.fragments_tested},
          {"fragments_hidden", c.fragments_hidden},
          {"fragments_clipped", c.fragments_clipped},
          {"beam_merges", c.beam_merges},
          {"beam_nodes", c.beam_nodes},
          {"beam_steps", c.beam_steps},
          {"beam_splits", c.beam_splits},
          {"beams_refused", c.beams_refused},
          {"covered", c.covered}};
}

}  // namespace bsp::experiments
