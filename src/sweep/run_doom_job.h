#pragma once
// Runs a Doom job (doom_job.h): one map's nodes built by one of our heuristics or an external
// builder, or the shipped ones read, all measured and proved by run_doom (doom_run.h). The record
// (analysis/SCHEMA.md, DOOM RUN):
//  - metrics: the nodes' sizes and depths, whoever built them; for ours also the segments built
//    from, the build's fallbacks and mixed leaves, the map errors left out, and what rounding
//    split vertices to integers did;
//  - invariants: the structural check (validate/doom_check.h); validation: our trees' Embree order
//    check, null for the others; `error` (top level) when an external builder failed or its output
//    could not be read;
//  - timings. Ours: kBuildSamples batches of the build and its conversion to vanilla lumps
//    (build_our_nodes), each at least kMinBatchSeconds of thread CPU, as builds are timed
//    (run_job.h), and gated the same way, planted slowdown included. An external builder: its
//    process's CPU time in kBuildSamples runs, reported and not gated, since it is not our code
//    and the gate would judge the machine's process start-up more than the builder. The shipped
//    nodes: none.
#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "sweep/job.h"
#include "sweep/run_job.h"

namespace bsp::sweep {

// job.doom must be set. Throws InputError for a missing IWAD or map.
nlohmann::json run_doom_job(const Job& job, const std::optional<PlantedSlowdown>& plant = {});

}  // namespace bsp::sweep
