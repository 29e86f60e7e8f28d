#pragma once
// The regression gate for the scaling benchmark (bench/bench_scaling.cpp): compares two Google
// Benchmark JSON outputs (--benchmark_out=FILE --benchmark_out_format=json) benchmark by benchmark,
// matched by name. Only what the benchmark makes comparable across machines is judged:
//  - ratios to an in-run reference (lower is better): build_vs_embree and its two parts,
//    choose_vs_embree and machinery_vs_embree (BuildStats), each a median over the
//    benchmark's runs divided by a median of its reference measured seconds apart in the same
//    process, and traverse_vs_embree_rays, the median of each run's ratio to the reference timed
//    right after it, so the machine's speed cancels. A ratio FAILS when it is worse than the
//    baseline's by at least the time tolerance (RegressOptions::time_tolerance), and a ratio better
//    by as much is a note. traverse_vs_sort and the 2-thread speedup are compared the same way but
//    only ever noted: a sort does not slow down with the machine as a traversal does, and on a
//    shared machine the second core is not ours;
//  - counts of the tree (fragments, bytes_per_fragment): deterministic, so they must match within
//    kFloatRelative.
// A baseline benchmark missing from the current output is a regression (run the same selection as
// the baseline, e.g. .ci/run's); a benchmark only the current output has is listed as new.
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "gate/regress.h"

namespace bsp::gate {

// True for a Google Benchmark JSON output (an object with a "benchmarks" array).
bool is_benchmark_output(const nlohmann::json& doc);

// Reads a Google Benchmark JSON output; InputError naming the file when it is not one.
nlohmann::json read_benchmark_output(const std::string& path);

// Throws UsageError when the tolerance is not > 1.
RegressResult compare_benchmarks(const nlohmann::json& baseline, const nlohmann::json& current,
                                 const RegressOptions& options);

}  // namespace bsp::gate
