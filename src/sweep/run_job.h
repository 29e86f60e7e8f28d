#pragma once
// Runs one job: generate the scene, build the tree, measure it, check its invariants and validate
// its back-to-front orders against Embree. The result is one run record (record.h): the job's
// identity, every metric, the invariant and validation results, and the timings apart: wall times
// (build_seconds from the builder, validation_seconds, job_seconds) and the CPU times of the
// calling thread for the build and the metrics (build_cpu_seconds, metrics_cpu_seconds), which the
// regression gate compares. Build and metrics are single-threaded, so their thread CPU time is
// their whole cost.
#include <nlohmann/json_fwd.hpp>

#include "sweep/job.h"

namespace bsp::sweep {

// Throws what the pieces throw (UsageError for a bad name or parameter; anything else is a bug the
// runner reports as a failed job).
nlohmann::json run_job(const Job& job);

}  // namespace bsp::sweep
