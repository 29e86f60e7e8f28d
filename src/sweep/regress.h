#pragma once
// The regression gate: compares a current report with a baseline, run by run (matched by job key).
//
// Deterministic fields (everything but timings, record.h) must match: integers, strings and
// booleans exactly; non-integer numbers (expected costs, mean depths) within kFloatRelative,
// because a sum's last bits may differ between compilers or library versions even though the tree
// is the same. Every current run must also have zero invariant and zero validation violations, and
// the current report no failed jobs. A baseline run missing from the current report is a
// regression; a run or field only the current report has is listed as new, not a regression.
//
// Timings: the CPU-time fields (ending in "_cpu_seconds", calibration.h) are compared as ratios to
// the calibration kernel each run was timed with:
//   r = (current / current calibration) / (baseline / baseline calibration).
// A timing is flagged when r >= tolerance (slower) or r <= 1 / tolerance (faster: an unexplained
// speed-up is as suspicious as a slow-down, e.g. work silently skipped), unless both it and the
// baseline are below the noise floor (in baseline-machine seconds), where clock granularity and
// cache effects dominate. Wall times are reported but not gated: on a shared machine they measure
// the other users as much as the code.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace bsp::sweep {

inline constexpr double kFloatRelative = 1e-9;

struct RegressOptions {
  double time_tolerance = 3.0;     // > 1
  double time_floor_seconds = 0.005;
};

struct Change {
  bool regression = false;  // false: listed for information (new runs or fields)
  std::string what;         // e.g. "changed", "slower", "missing run"
  std::string run;          // scene heuristic shape n seed
  std::string field;
  std::string baseline, current;
};

struct RegressResult {
  std::vector<Change> changes;
  std::uint64_t runs_compared = 0;
  std::uint64_t values_compared = 0;
  std::uint64_t timings_compared = 0;
  std::uint64_t timings_below_floor = 0;
  bool failed() const;
};

// Throws UsageError when the tolerance is not > 1 or the floor is negative.
RegressResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current,
                              const RegressOptions& options);
// The table of changes, then one summary line.
void print_regress(const RegressResult& result, std::ostream& out);

}  // namespace bsp::sweep
