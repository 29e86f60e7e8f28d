#pragma once
// Runs one merge job (job.h): generates the pair's two operands, builds each as a solid tree with
// the job's heuristic (one splitter, seeded by the job, builds both, as `bspbench merge` does),
// merges them by the job's set operation [Naylor1990], and proves the result against CGAL
// (validate/solid_check.h: the job's points against exact side-of-mesh answers, the volume against
// corefinement, the boundary closed). The record (analysis/SCHEMA.md) holds the operands' tree
// sizes and the merge cost (partitionTree calls, sub-hyperplane splits, nodes visited, result size
// before and after reduction) as metrics, the boundary check as invariants and the proof as
// validation.
//
// Merge timing, as run_job.h times builds: kBuildSamples batches of repeated merges (merge and
// reduce, on the same operand trees), each at least kMinBatchSeconds of thread CPU time; the gate
// compares these samples.
#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "sweep/job.h"
#include "sweep/run_job.h"

namespace bsp::sweep {

// job.op must be set. Throws what the pieces throw.
nlohmann::json run_merge_job(const Job& job, const std::optional<PlantedSlowdown>& plant = {});

}  // namespace bsp::sweep
