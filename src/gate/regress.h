#pragma once
// The regression gate: compares a current report with a baseline, run by run (matched by job key)
// for results, group by group for build times.
//
// Deterministic fields (everything but the timings declared in record.h) must match: integers,
// strings and booleans exactly; non-integer numbers (expected costs, mean depths) within
// kFloatRelative, because a sum's last bits may differ between compilers or library versions even
// though the tree is the same. Every current run must also have zero invariant violations, zero
// validation violations and zero ray-shooting mismatches (but a Doom run of nodes made by others:
// their violations are facts about them, judged_for_violations in record.h), and the current report
// no failed jobs. A baseline run missing from the current report is a regression; a run or field
// only the current report has is listed as new, not a regression.
//
// Build times are judged per group (scene x heuristic x shape, pooling sizes and seeds), never per
// run against a fixed factor. Each run holds kBuildSamples thread-CPU samples per build
// (experiments/timing.h); a merge run holds as many per merge (experiments/merge/merge.h), grouped by pair x heuristic
// x operation and judged the same way, and a Doom run of our heuristic as many per build of the
// map's nodes, grouped by IWAD x heuristic label (maps pooled). Every sample is divided by the
// in-run reference timed just before its batch (experiments/timing.h, reference_build.h), so a
// slower or faster machine, and a machine whose speed changes while it runs, cancels out; when
// either run has no references (a report made before them), both runs' samples are divided by
// their sweeps' calibration kernel times (sweep/calibration.h) instead, which follows a machine's
// speed only as it was when the sweep started. Then each is divided by the median normalized
// baseline sample of the same job, so a group's sizes and seeds share one scale: baseline values
// scatter around 1 and a job k times slower gives values around k. The
// group's pooled baseline and current values are compared with the two-sided Mann–Whitney U test
// (metrics/statistics.h), as Google Benchmark's compare.py compares repetitions. The slowdown is
// the ratio of the pooled medians (current over baseline). A group FAILS only when it is both
// significant (p < alpha) and slowed by at least time_tolerance; a significant speed-up by the same
// factor is listed as a note, since faster code is not a regression but may show skipped work.
// Significance alone is not enough: two sweeps of the same code differ by a few percent (caches
// shared with other processes), which thirty samples per group make "significant"; the tolerance
// says how much slower matters.
//
// Wall times and the other CPU times (metrics) are reported but not gated: on a shared machine the
// wall time measures the other users as much as the code, and the metrics' cost is not the
// product.
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace bsp::gate {

inline constexpr double kFloatRelative = 1e-9;

// How runs of the two reports are paired. The gate pairs by job key, which covers the heuristic's
// resolved parameters, so a changed default makes the affected runs missing and new. A comparison
// meant to show such a change (bspbench report --baseline) pairs by the run's command, which names
// only what the suite sets, with its validation views (the one setting a command leaves out).
enum class RunMatch { Key, Command };

struct RegressOptions {
  double time_tolerance = 1.5;  // the slowdown (ratio of medians) that fails a significant group; > 1
  double alpha = 0.05;          // significance level of the Mann–Whitney test; in (0, 1)
  RunMatch match = RunMatch::Key;
};

struct Change {
  bool regression = false;  // false: listed for information (new runs or fields, speed-ups)
  std::string what;         // e.g. "changed", "slower", "missing run"
  std::string run;          // scene heuristic shape n seed, or scene heuristic shape for a timing group
  std::string field;
  std::string baseline, current;
};

// One timing group's test, significant or not, for reports that show every group (bspbench report
// --baseline), not only the gate's findings.
struct TimingTest {
  std::string group;  // scene heuristic shape
  std::string field;
  std::uint64_t baseline_samples = 0, current_samples = 0;
  double ratio = 1;  // median current over median baseline, both on the baseline job's scale
  double p = 1;      // two-sided Mann–Whitney
  std::string verdict;  // "slower" (fails the gate), "faster", or "within" (not significant or within tolerance)
};

struct RegressResult {
  std::vector<Change> changes;
  std::vector<TimingTest> timing_tests;
  std::uint64_t runs_compared = 0;
  std::uint64_t values_compared = 0;
  std::uint64_t timing_groups = 0;   // groups whose build times were tested
  std::uint64_t timing_samples = 0;  // current build samples in those groups
  std::uint64_t timing_pairs = 0;    // matched runs in those groups
  std::uint64_t timing_pairs_by_reference = 0;  // of those, compared against their in-run references
  bool benchmarks = false;           // runs are benchmarks of two Google Benchmark outputs (bench_gate.h)
  bool failed() const;
};

// Throws UsageError when the tolerance is not > 1 or alpha not in (0, 1), InputError when runs are
// matched by command and two runs of one report share a command and views.
RegressResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current,
                              const RegressOptions& options);
// The baseline that stands for several reports of one suite on one machine, oldest first (regress
// --history): the newest report, each of its runs' gated timing samples and their references pooled
// from every report holding the run. Each report's samples and references are scaled by the newest
// report's calibration over its own, so a comparison by calibration stays on one scale and one by
// reference is unchanged. Throws InputError for no reports.
nlohmann::json pool_reports(std::span<const nlohmann::json* const> reports);

// A run's timing group and gated samples, each divided by its batch's reference (by the calibration
// when the run has no references): what the history's timing series are made of.
struct RunTiming {
  std::string group;  // as the gate groups runs: scene heuristic shape
  std::vector<double> samples;
};
RunTiming run_timing(const nlohmann::json& run);

// Every change and timing test as JSON, for the report's comparison section.
nlohmann::json to_json(const RegressResult& result);
// Three significant digits: how the gate's tables show numbers.
std::string number_text(double v);
// The table of changes, then one summary line.
void print_regress(const RegressResult& result, std::ostream& out);

}  // namespace bsp::gate
