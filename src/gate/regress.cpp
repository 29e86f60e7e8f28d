#include "gate/regress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "metrics/statistics.h"
#include "results/record.h"

namespace bsp::gate {

std::string number_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

namespace {

// Sections of a run record compared exactly (record.h); "error" is a Doom run's failed external builder.
constexpr const char* kDeterministicSections[] = {"id", "metrics", "invariants", "validation", "ray_shooting", "error"};
// Counts in a current run that must be zero: section, field.
constexpr std::pair<const char*, const char*> kMustBeZero[] = {
    {"invariants", "violations"}, {"validation", "violations"}, {"ray_shooting", "mismatches"}};

// The timing group of a run (regress.h): scene, heuristic and what its kind groups by in place of
// the shape (experiments/kind.h: a merge run's operation, an animate run's update strategy, a fixed
// word for occlude and Doom runs, whose sizes or maps pool), and the kernel when it is not float.
std::string group_label(const nlohmann::json& id) {
  const experiments::Kind* kind = results::kind_of(id);
  const std::string shape = !kind                              ? id.value("shape", "?")
                            : !kind->timing_group_word.empty() ? std::string(kind->timing_group_word)
                                                               : id.value(std::string(kind->timing_group_field), "?");
  // A run of the exact kernel (a drawing or merge run with --kernel exact) is timed apart from the
  // float runs beside it.
  std::string label = id.value("scene", "?") + " " + id.value("heuristic", "?") + " " + shape;
  if (id.contains("kernel")) label.append(" ").append(id.value("kernel", "?"));
  return label;
}

std::string run_label(const nlohmann::json& id) {
  const experiments::Kind* kind = results::kind_of(id);
  const std::string field(kind ? kind->instance_field : "n");
  const std::string instance = field == "n" ? "n=" + id.value("n", nlohmann::json()).dump() : id.value(field, "?");
  return group_label(id) + " " + instance + " seed=" + id.value("seed", nlohmann::json()).dump();
}

// A section of a run, or null when the run has none.
const nlohmann::json& section_of(const nlohmann::json& run, const char* section) {
  static const nlohmann::json none;
  return run.contains(section) ? run[section] : none;
}

// A group's normalized samples, each divided by its job's median normalized baseline sample.
struct TimingGroup {
  std::string field;  // the gated timing
  std::vector<double> baseline, current;
  std::uint64_t pairs = 0;       // matched pairs of runs with samples on both sides
  std::uint64_t references = 0;  // of those, pairs divided by their references, not by calibration
};

struct Comparer {
  RegressResult& result;
  std::string run;

  void note(bool regression, std::string what, std::string field, std::string base, std::string cur) {
    result.changes.push_back({regression, std::move(what), run, std::move(field), std::move(base), std::move(cur)});
  }

  static bool same_number(const nlohmann::json& b, const nlohmann::json& c) {
    if (b.is_number_integer() && c.is_number_integer()) return b == c;
    const double x = b.get<double>(), y = c.get<double>();
    return x == y || std::abs(x - y) <= kFloatRelative * std::max(std::abs(x), std::abs(y));
  }

  void values(const nlohmann::json& b, const nlohmann::json& c, const std::string& path) {
    if (b.is_object() && c.is_object()) {
      for (const auto& [k, v] : b.items()) {
        if (c.contains(k)) values(v, c[k], path + "." + k);
        else note(true, "field missing", path + "." + k, v.dump(), "");
      }
      for (const auto& [k, v] : c.items())
        if (!b.contains(k)) note(false, "new field", path + "." + k, "", v.dump());
      return;
    }
    if (b.is_array() && c.is_array() && b.size() == c.size()) {
      for (std::size_t i = 0; i < b.size(); ++i) values(b[i], c[i], path + "[" + std::to_string(i) + "]");
      return;
    }
    ++result.values_compared;
    const bool same = b.is_number() && c.is_number() ? same_number(b, c) : b == c;
    if (!same) note(true, "changed", path, b.dump(), c.dump());
  }

  void violations(const nlohmann::json& current) {
    if (!results::judged_for_violations(section_of(current, "id"))) return;
    for (const auto& [section, field] : kMustBeZero) {
      const auto& s = section_of(current, section);
      if (s.is_object() && s.value(field, std::uint64_t{0}) > 0)
        note(true, "violations", std::string(section) + "." + field, "", s[field].dump());
    }
  }
};

// The gated samples of a run: its kind's GatedSamples timing (a drawing run's builds, a merge run's
// merges, an animate run's updates, an occlude run's cullings, a Doom run's builds by our
// heuristic; an external builder's runs are not ours to gate, and the shipped nodes are not timed).
std::string gated_field(const nlohmann::json& run) {
  return std::string(results::timing_of_role(section_of(run, "id"), experiments::TimingRole::GatedSamples));
}

// The run's timing `field` as numbers; empty when it has none or any entry is not a positive number.
std::vector<double> positive_numbers(const nlohmann::json& run, std::string_view field) {
  const auto& values = section_of(run, "timings").value(std::string(field), nlohmann::json::array());
  std::vector<double> out;
  for (const auto& v : values) {
    if (!v.is_number() || !(v.get<double>() > 0)) return {};
    out.push_back(v.get<double>());
  }
  return out;
}

// The reference sample of each gated sample of the run (experiments/timing.h); empty when the run
// has none for every sample (reports made before the references, external work).
std::vector<double> reference_samples(const nlohmann::json& run) {
  const auto field = results::timing_of_role(section_of(run, "id"), experiments::TimingRole::ReferenceSamples);
  std::vector<double> out = field.empty() ? std::vector<double>{} : positive_numbers(run, field);
  const auto& gated = section_of(run, "timings").value(gated_field(run), nlohmann::json::array());
  if (out.size() != gated.size()) out.clear();
  return out;
}

// The gated samples of a run, each divided by its batch's reference sample when `by_reference`,
// else by the sweep's calibration time; empty when it has none.
std::vector<double> normalized_samples(const nlohmann::json& run, bool by_reference) {
  std::vector<double> out;
  const auto& samples = section_of(run, "timings").value(gated_field(run), nlohmann::json::array());
  const std::vector<double> reference = by_reference ? reference_samples(run) : std::vector<double>{};
  const double calibration = run["calibration_seconds"].get<double>();
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (samples[i].is_number()) out.push_back(samples[i].get<double>() / (by_reference ? reference[i] : calibration));
  return out;
}

// Adds a matched pair of runs to its timing group, on the scale of the baseline job's median. Both
// runs are divided by their batches' references when both have them; otherwise (a baseline made
// before the references) both by their sweeps' calibrations, so the two are always alike.
void add_timings(const nlohmann::json& b, const nlohmann::json& c, TimingGroup& group) {
  group.field = "timings." + gated_field(b);
  const bool by_reference = !reference_samples(b).empty() && !reference_samples(c).empty();
  const std::vector<double> base = normalized_samples(b, by_reference), cur = normalized_samples(c, by_reference);
  const double scale = median(base);
  if (base.empty() || cur.empty() || !(scale > 0)) return;
  ++group.pairs;
  group.references += by_reference;
  for (double x : base) group.baseline.push_back(x / scale);
  for (double x : cur) group.current.push_back(x / scale);
}

void judge_timings(const std::map<std::string, TimingGroup>& groups, const RegressOptions& options,
                   RegressResult& result) {
  for (const auto& [label, g] : groups) {
    if (g.baseline.empty() || g.current.empty()) continue;
    ++result.timing_groups;
    result.timing_samples += g.current.size();
    result.timing_pairs += g.pairs;
    result.timing_pairs_by_reference += g.references;
    const double ratio = median(g.current) / median(g.baseline);
    const MannWhitney test = mann_whitney_u(g.current, g.baseline);
    const bool slower = test.p < options.alpha && ratio >= options.time_tolerance;
    const bool faster = test.p < options.alpha && ratio <= 1 / options.time_tolerance;
    result.timing_tests.push_back({label, g.field, g.baseline.size(), g.current.size(), ratio, test.p,
                                   slower ? "slower" : faster ? "faster" : "within"});
    if (!(test.p < options.alpha)) continue;
    const std::string base = "median 1 (" + std::to_string(g.baseline.size()) + " samples)";
    // Appended, not `"x" + string`: GCC 12 warns falsely (-Wrestrict) on that operator+ when inlined.
    std::string cur = "x";
    cur += number_text(ratio) + " (p=" + number_text(test.p) + ")";
    if (ratio >= options.time_tolerance)
      result.changes.push_back({true, "slower", label, g.field, base, cur});
    else if (ratio <= 1 / options.time_tolerance)
      result.changes.push_back({false, "faster", label, g.field, base, cur});
  }
}

// A run's command with its validation views, which the command does not name: two blocks of a
// suite may differ only in those.
std::string command_key(const nlohmann::json& id) {
  return id["command"].get<std::string>() + " (views " + id.value("validation_views", nlohmann::json()).dump() + ")";
}

std::map<std::string, const nlohmann::json*> by_key(const nlohmann::json& records, RunMatch match) {
  std::map<std::string, const nlohmann::json*> out;
  for (const auto& r : records) {
    const std::string key = match == RunMatch::Command ? command_key(r["id"]) : r["key"].get<std::string>();
    if (!out.emplace(key, &r).second) throw InputError("two runs of one report share the command " + key);
  }
  return out;
}

void compare_runs(const nlohmann::json& baseline, const nlohmann::json& current, const RegressOptions& options,
                  RegressResult& result) {
  const auto base = by_key(baseline["runs"], options.match), cur = by_key(current["runs"], options.match);
  std::map<std::string, TimingGroup> groups;
  for (const auto& [key, b] : base) {
    Comparer cmp{result, run_label((*b)["id"])};
    const auto it = cur.find(key);
    if (it == cur.end()) {
      cmp.note(true, "missing run", "", key, "");
      continue;
    }
    ++result.runs_compared;
    for (const char* s : kDeterministicSections) cmp.values(section_of(*b, s), section_of(*it->second, s), s);
    cmp.violations(*it->second);
    add_timings(*b, *it->second, groups[group_label((*b)["id"])]);
  }
  for (const auto& [key, c] : cur)
    if (!base.count(key)) Comparer{result, run_label((*c)["id"])}.note(false, "new run", "", "", key);
  judge_timings(groups, options, result);
}

}  // namespace

nlohmann::json pool_reports(std::span<const nlohmann::json* const> reports) {
  if (reports.empty()) throw InputError("no reports to pool");
  nlohmann::json pooled = *reports.back();
  const auto calibration = [](const nlohmann::json& run) { return run.value("calibration_seconds", 0.0); };
  std::map<std::string, std::vector<const nlohmann::json*>> older;
  for (std::size_t i = 0; i + 1 < reports.size(); ++i)
    for (const auto& r : (*reports[i])["runs"]) older[r["key"].get<std::string>()].push_back(&r);
  for (auto& run : pooled["runs"]) {
    const auto it = older.find(run["key"].get<std::string>());
    const std::string gated = gated_field(run);
    if (it == older.end() || gated.empty() || !(calibration(run) > 0)) continue;
    const auto ref_field = results::timing_of_role(section_of(run, "id"), experiments::TimingRole::ReferenceSamples);
    const bool references = !ref_field.empty() && !reference_samples(run).empty();
    auto& timings = run["timings"];
    for (const nlohmann::json* old : it->second) {
      const double scale = calibration(run) / calibration(*old);
      if (!(scale > 0) || !std::isfinite(scale)) continue;
      const std::vector<double> refs = reference_samples(*old);
      if (references && refs.empty()) continue;  // its samples could not be divided like the others
      const auto& samples = section_of(*old, "timings").value(gated, nlohmann::json::array());
      if (!std::all_of(samples.begin(), samples.end(), [](const nlohmann::json& x) { return x.is_number(); })) continue;
      for (const auto& x : samples) timings[gated].push_back(x.get<double>() * scale);
      if (references)
        for (double x : refs) timings[std::string(ref_field)].push_back(x * scale);
    }
  }
  return pooled;
}

RunTiming run_timing(const nlohmann::json& run) {
  const bool by_reference = !reference_samples(run).empty();
  return {group_label(section_of(run, "id")), gated_field(run).empty() ? std::vector<double>{} : normalized_samples(run, by_reference)};
}

bool RegressResult::failed() const {
  return std::any_of(changes.begin(), changes.end(), [](const Change& c) { return c.regression; });
}

nlohmann::json to_json(const RegressResult& result) {
  nlohmann::json changes = nlohmann::json::array(), timings = nlohmann::json::array();
  for (const Change& c : result.changes)
    changes.push_back({{"regression", c.regression}, {"what", c.what}, {"run", c.run}, {"field", c.field},
                       {"baseline", c.baseline}, {"current", c.current}});
  for (const TimingTest& t : result.timing_tests)
    timings.push_back({{"group", t.group}, {"field", t.field}, {"baseline_samples", t.baseline_samples},
                       {"current_samples", t.current_samples}, {"ratio", t.ratio}, {"p", t.p}, {"verdict", t.verdict}});
  return {{"changes", changes}, {"timing_tests", timings}, {"runs_compared", result.runs_compared},
          {"values_compared", result.values_compared}, {"timing_groups", result.timing_groups},
          {"timing_samples", result.timing_samples}, {"timing_pairs", result.timing_pairs},
          {"timing_pairs_by_reference", result.timing_pairs_by_reference}, {"failed", result.failed()}};
}

RegressResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current,
                              const RegressOptions& options) {
  if (!(options.time_tolerance > 1)) throw UsageError("--time-tolerance must be greater than 1");
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be between 0 and 1");
  RegressResult result;
  if (baseline["suite"] != current["suite"])
    result.changes.push_back({false, "other suite", "", "suite", baseline["suite"].dump(), current["suite"].dump()});
  compare_runs(baseline, current, options, result);
  for (const auto& f : current["failures"])
    result.changes.push_back({true, "job failed", run_label(f["id"]), "error", "", f.value("error", "")});
  return result;
}

void print_regress(const RegressResult& result, std::ostream& out) {
  std::size_t w_what = 6, w_run = 3, w_field = 5, w_base = 8;
  for (const auto& c : result.changes) {
    w_what = std::max(w_what, c.what.size());
    w_run = std::max(w_run, c.run.size());
    w_field = std::max(w_field, c.field.size());
    w_base = std::max(w_base, c.baseline.size());
  }
  const auto row = [&](const std::string& verdict, const std::string& what, const std::string& run,
                       const std::string& field, const std::string& base, const std::string& cur) {
    out << verdict << "  " << what << std::string(w_what - what.size(), ' ') << "  " << run
        << std::string(w_run - run.size(), ' ') << "  " << field << std::string(w_field - field.size(), ' ') << "  "
        << base << std::string(w_base - base.size(), ' ') << "  " << cur << "\n";
  };
  if (!result.changes.empty()) row("verdict", "change", "run", "field", "baseline", "current");
  for (const auto& c : result.changes) row(c.regression ? "FAIL   " : "note   ", c.what, c.run, c.field, c.baseline, c.current);
  out << "regress: " << result.runs_compared << (result.benchmarks ? " benchmarks, " : " runs, ")
      << result.values_compared << " values";
  if (!result.benchmarks)
    out << ", " << result.timing_groups << " build-time groups (" << result.timing_samples << " samples; "
        << result.timing_pairs_by_reference << " of " << result.timing_pairs << " runs against their in-run reference)";
  out << " compared; " << (result.failed() ? "REGRESSION" : "no regression") << "\n";
}

}  // namespace bsp::gate
