#pragma once
// Runs a suite (or one shard of it): measures the calibration kernel, skips the jobs its journal
// already holds, runs the others in parallel with OpenMP (one job per thread at a time, dynamic
// schedule; parallel regions inside a job run single-threaded), journals each as it ends and
// assembles the report. Deterministic fields do not depend on the thread count, the sharding or
// how often the sweep was interrupted and resumed.
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "experiments/job.h"
#include "suite/expand.h"
#include "suite/suite.h"

namespace bsp::sweep {

struct SweepOptions {
  int threads = 0;  // 0: OpenMP's default (OMP_NUM_THREADS or the core count)
  std::optional<suite::Shard> shard;
  // The journal lives here, in a file named after the suite, its definition hash, this executable's
  // hash and the shard, so only the same command of the same build resumes it.
  std::string journal_dir = "results/journal";
  bool fresh = false;  // discard the journal first
  std::ostream* log = nullptr;  // progress and notes; nullptr for silence
  bool log_is_terminal = false;
  std::optional<experiments::PlantedSlowdown> plant;  // TEST ONLY (experiments/timing.h); named in the journal and the report
};

// The report (results/report.h). A job that throws is listed under "failures" and not journaled, so the
// next run retries it. Throws InputError when the journal cannot be read or written.
nlohmann::json run_sweep(const suite::Suite& suite, const SweepOptions& options);

// Where run_sweep keeps the journal for these options.
std::string journal_path(const suite::Suite& suite, const SweepOptions& options);

}  // namespace bsp::sweep
