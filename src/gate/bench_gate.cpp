#include "gate/bench_gate.h"

#include <cmath>
#include <optional>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "common/errors.h"

namespace bsp::gate {

namespace {

enum class Better { Lower, Higher };

struct Ratio {
  const char* name;
  Better better;
  bool gated;  // false: a change is listed as a note only
};

// The ratio counters the gate compares. The build's bill (choose_vs_embree, machinery_vs_embree) is
// gated part by part, so a slower heuristic and a slower core each fail by name. The speed-up on two threads is not gated: on a shared
// machine the second core is not ours, and a lost core shows in build_vs_embree at threads:2
// anyway, since Embree's reference runs on as many threads and shares the loss. The build's peak
// resident memory over the tree's bytes is gated with the same tolerance: it moves little between
// runs, but page-granular accounting makes it less than exact. The traversal is gated against
// Embree's primary rays timed after each of its runs, not against std::sort: on a virtual machine
// the traversal's speed drifts by up to 2x between runs while a sort's barely moves, and Embree's
// traversal of its BVH drifts with ours (docs/results/gate-timing.md); traverse_vs_sort, the
// figure a renderer choosing between a BSP and a depth sort wants, is listed when it moves. So is
// the heuristic's rate of side tests over this machine's compute ceiling (bench/roofline.h), whose
// kernels do not drift with the build's code the way Embree's build does.
constexpr Ratio kRatios[] = {{"build_vs_embree", Better::Lower, true},
                             {"choose_vs_embree", Better::Lower, true},
                             {"machinery_vs_embree", Better::Lower, true},
                             {"traverse_vs_embree_rays", Better::Lower, true},
                             {"traverse_vs_sort", Better::Lower, false},
                             {"build_peak_vs_tree", Better::Lower, true},
                             {"speedup", Better::Higher, false},
                             {"choose_rate_vs_compute", Better::Higher, false}};
// Deterministic counters of the tree and of the build's work.
constexpr const char* kCounts[] = {"fragments",
                                   "side_tests",
                                   "bytes_per_fragment",
                                   "position_bytes_per_fragment",
                                   "attribute_bytes_per_fragment",
                                   "record_bytes_per_fragment",
                                   "node_bytes_per_fragment",
                                   "plane_bytes_per_fragment"};

// Benchmarks by name; aggregates of repetitions (mean, median, stddev rows) are skipped, as the
// ratios are medians already.
std::map<std::string, const nlohmann::json*> by_name(const nlohmann::json& doc) {
  std::map<std::string, const nlohmann::json*> out;
  for (const auto& b : doc["benchmarks"])
    if (b.is_object() && b.contains("name") && b["name"].is_string() && b.value("run_type", "iteration") == "iteration")
      out[b["name"].get<std::string>()] = &b;
  return out;
}

std::optional<double> counter(const nlohmann::json& b, const char* name) {
  if (!b.contains(name) || !b[name].is_number()) return std::nullopt;
  return b[name].get<double>();
}

struct BenchComparer {
  RegressResult& result;
  const RegressOptions& options;
  std::string name;

  void add(bool regression, std::string what, std::string field, std::string base, std::string cur) {
    result.changes.push_back({regression, std::move(what), name, std::move(field), std::move(base), std::move(cur)});
  }

  void ratio(const Ratio& r, double base, double cur) {
    ++result.values_compared;
    if (!(base > 0) || !(cur > 0)) {
      if (!(cur > 0)) add(r.gated, "not positive", r.name, number_text(base), number_text(cur));
      return;
    }
    const double worse = r.better == Better::Lower ? cur / base : base / cur;
    if (worse >= options.time_tolerance) add(r.gated, "worse", r.name, number_text(base), number_text(cur));
    else if (1.0 / worse >= options.time_tolerance) add(false, "better", r.name, number_text(base), number_text(cur));
  }

  void count(const char* field, double base, double cur) {
    ++result.values_compared;
    if (std::abs(cur - base) > kFloatRelative * std::max(std::abs(base), std::abs(cur)))
      add(true, "changed", field, number_text(base), number_text(cur));
  }

  void compare(const nlohmann::json& base, const nlohmann::json& cur) {
    for (const Ratio& r : kRatios) {
      const auto b = counter(base, r.name), c = counter(cur, r.name);
      if (b && c) ratio(r, *b, *c);
      else if (b) add(r.gated, "missing", r.name, number_text(*b), "-");
    }
    for (const char* field : kCounts) {
      const auto b = counter(base, field), c = counter(cur, field);
      if (b && c) count(field, *b, *c);
      else if (b) add(true, "missing", field, number_text(*b), "-");
    }
  }
};

}  // namespace

bool is_benchmark_output(const nlohmann::json& doc) {
  return doc.is_object() && doc.contains("benchmarks") && doc["benchmarks"].is_array();
}

nlohmann::json read_benchmark_output(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the benchmark output");
  nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (doc.is_discarded()) throw InputError(path + ": not valid JSON");
  if (!is_benchmark_output(doc)) throw InputError(path + ": not a Google Benchmark JSON output (no \"benchmarks\" array)");
  return doc;
}

RegressResult compare_benchmarks(const nlohmann::json& baseline, const nlohmann::json& current,
                                 const RegressOptions& options) {
  if (!(options.time_tolerance > 1.0)) throw UsageError("the time tolerance must be > 1");
  RegressResult result;
  result.benchmarks = true;
  const auto base = by_name(baseline), cur = by_name(current);
  for (const auto& [name, b] : base) {
    BenchComparer c{result, options, name};
    const auto it = cur.find(name);
    if (it == cur.end()) {
      c.add(true, "missing benchmark", "", "present", "-");
      continue;
    }
    ++result.runs_compared;
    c.compare(*b, *it->second);
  }
  for (const auto& [name, b] : cur)
    if (!base.count(name)) result.changes.push_back({false, "new benchmark", name, "", "-", "present"});
  return result;
}

}  // namespace bsp::gate
