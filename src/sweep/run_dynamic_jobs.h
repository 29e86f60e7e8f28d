#pragma once
// Runs an animate job or an occlude job (job.h). Records follow analysis/SCHEMA.md:
//  - animate: the run of sweep/animation_run.h. Metrics are the frames' sizes, culled cost, the
//    updates' work totals (work_*) and the drift from a fresh build at the last drift frame
//    (drift_*); invariants and validation count the checked frames' violations; the gate compares
//    the per-frame update CPU times (update_cpu_samples, frames 1 on, one sample per update).
//  - occlude: each metric view of sweep/occlusion_run.h, summed (emitted, frustum_culled,
//    seen_by_embree and the culling's counters) with the mean ratios; invariants are the tree's;
//    validation is the Embree proof (violations: rays whose first hit was culled); the gate
//    compares timed batches of culling every view (occlude_cpu_samples), as builds are timed.
#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "sweep/job.h"
#include "sweep/run_job.h"

namespace bsp::sweep {

// job.animate must be set. The planted slowdown does not apply: updates are not timed in batches.
nlohmann::json run_animate_job(const Job& job);
// job.occlude must be set.
nlohmann::json run_occlude_job(const Job& job, const std::optional<PlantedSlowdown>& plant = {});

}  // namespace bsp::sweep
