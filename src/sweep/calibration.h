#pragma once
// The calibration kernel: a fixed, deterministic CPU workload that uses none of bspbench's code,
// timed at the start of every sweep and stored with its runs. The regression gate compares timings
// as ratios to it, so a report from a slower machine does not read as a regression.
//
// Times are CPU times of the calling thread, not wall times: on a shared machine the wall time of a
// job depends on what else runs, its CPU time much less. The gated timings (the run fields ending in
// "_cpu_seconds") are measured the same way, around single-threaded work.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/cpu_time.h"

namespace bsp::sweep {

struct Calibration {
  double seconds = 0;           // thread CPU time of the best repetition: the least disturbed one
  std::uint64_t checksum = 0;   // the kernel's result; identical everywhere, keeps the work observable
};

// About 0.15 s per repetition on the 2-core reference machine.
Calibration calibrate();
nlohmann::json to_json(const Calibration& c);
// What the kernel does, stored in reports beside its time.
std::string calibration_kernel_description();

}  // namespace bsp::sweep
