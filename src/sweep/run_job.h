#pragma once
// Runs one job: generate the scene, build the tree, measure it, check its invariants, validate its
// back-to-front orders against Embree and cross-check its ray shooting against Embree's first hits
// (on at most 1500 of the validation's rays, evenly strided: run_job.cpp says why).
// The result is one run record (record.h): the job's identity, every metric, the invariant,
// validation and ray-shooting results, and the timings apart.
//
// Build timing. The gate (regress.h) compares build CPU times statistically, so each run times the
// build beyond the first (the tree that is measured, which also warms the caches): kBuildSamples
// batches, each repeating the build until at least kMinBatchSeconds of thread CPU time have passed.
// A sample is a batch's CPU time divided by its build count: the time per build over at least 2 ms,
// a thousand times the scheduler's accounting granularity, so 0.05 ms builds are measurable too.
// build_cpu_seconds is the samples' median, build_cpu_builds the builds timed. Thread CPU time, not
// wall time: on a shared machine the wall time measures the other users as much as the code. Build
// and metrics are single-threaded, so their thread CPU time is their whole cost.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "sweep/job.h"

namespace bsp::sweep {

inline constexpr int kBuildSamples = 5;
inline constexpr double kMinBatchSeconds = 0.002;

// TEST ONLY: makes every timed build batch of one heuristic cost `factor` times its CPU time, by
// burning (factor - 1) times the batch's CPU time inside the timed region, so tests can show that
// the gate catches a slowdown. Set through the BSPBENCH_PLANT_SLOWDOWN environment variable of
// `bspbench sweep` (heuristic:factor, e.g. naylor:1.5); never in a baseline. A report made with it
// names it in its shard section ("planted_slowdown").
struct PlantedSlowdown {
  std::string heuristic;
  double factor = 1;  // >= 1
};
// Parses "heuristic:factor"; throws UsageError naming the variable.
PlantedSlowdown parse_planted_slowdown(const std::string& text);

// The timed batches described above, of any work: kBuildSamples batches, each repeating `work`
// until kMinBatchSeconds of thread CPU have passed, burning (plant - 1) times each batch's CPU
// time when plant > 1 (the planted slowdown).
struct TimedBatches {
  std::vector<double> samples;  // CPU seconds per run of `work`, one per batch
  std::uint64_t runs = 0;       // runs timed in all
  double median() const;
};
TimedBatches time_batches(const std::function<void()>& work, double plant = 1.0);

// Throws what the pieces throw (UsageError for a bad name or parameter; anything else is a bug the
// runner reports as a failed job). A merge job (job.op set) runs run_merge_job.h, animate and occlude
// jobs run_dynamic_jobs.h, Doom jobs run_doom_job.h.
nlohmann::json run_job(const Job& job, const std::optional<PlantedSlowdown>& plant = {});

}  // namespace bsp::sweep
