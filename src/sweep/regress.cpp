#include "sweep/regress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string_view>

#include "common/errors.h"

namespace bsp::sweep {

namespace {

// Sections of a run record compared exactly (record.h).
constexpr const char* kDeterministicSections[] = {"id", "metrics", "invariants", "validation"};
// A ratio computed from stored doubles can land a rounding error short of the tolerance it was
// made to reach (a timing divided by exactly 3); this relative slack absorbs that.
constexpr double kRatioSlack = 1e-12;
// The timings the gate compares (regress.h).
constexpr std::string_view kGatedTimingSuffix = "_cpu_seconds";

std::string run_label(const nlohmann::json& id) {
  return id.value("scene", "?") + " " + id.value("heuristic", "?") + " " + id.value("shape", "?") +
         " n=" + id.value("n", nlohmann::json()).dump() + " seed=" + id.value("seed", nlohmann::json()).dump();
}

std::string number_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

struct Comparer {
  const RegressOptions& options;
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
    for (const char* section : {"invariants", "validation"}) {
      const auto& s = current[section];
      if (s.is_object() && s.value("violations", std::uint64_t{0}) > 0)
        note(true, "violations", std::string(section) + ".violations", "", s["violations"].dump());
    }
  }

  void timings(const nlohmann::json& b, const nlohmann::json& c) {
    const double scale = b["calibration_seconds"].get<double>() / c["calibration_seconds"].get<double>();
    for (const auto& [k, v] : b["timings"].items()) {
      if (!k.ends_with(kGatedTimingSuffix) || !c["timings"].contains(k) || !v.is_number() ||
          !c["timings"][k].is_number())
        continue;
      const double base = v.get<double>(), cur = c["timings"][k].get<double>() * scale;
      if (std::max(base, cur) < options.time_floor_seconds) {
        ++result.timings_below_floor;
        continue;
      }
      ++result.timings_compared;
      const double ratio = cur / base, tol = options.time_tolerance;
      if (ratio >= tol * (1 - kRatioSlack))
        note(true, "slower", "timings." + k, number_text(base), number_text(cur) + " (x" + number_text(ratio) + ")");
      else if (ratio <= (1 + kRatioSlack) / tol)
        note(true, "faster", "timings." + k, number_text(base), number_text(cur) + " (x" + number_text(ratio) + ")");
    }
  }
};

std::map<std::string, const nlohmann::json*> by_key(const nlohmann::json& records) {
  std::map<std::string, const nlohmann::json*> out;
  for (const auto& r : records) out[r["key"].get<std::string>()] = &r;
  return out;
}

void compare_runs(const nlohmann::json& baseline, const nlohmann::json& current, const RegressOptions& options,
                  RegressResult& result) {
  const auto base = by_key(baseline["runs"]), cur = by_key(current["runs"]);
  for (const auto& [key, b] : base) {
    Comparer cmp{options, result, run_label((*b)["id"])};
    const auto it = cur.find(key);
    if (it == cur.end()) {
      cmp.note(true, "missing run", "", key, "");
      continue;
    }
    ++result.runs_compared;
    for (const char* s : kDeterministicSections) cmp.values((*b)[s], (*it->second)[s], s);
    cmp.violations(*it->second);
    cmp.timings(*b, *it->second);
  }
  for (const auto& [key, c] : cur)
    if (!base.count(key)) Comparer{options, result, run_label((*c)["id"])}.note(false, "new run", "", "", key);
}

}  // namespace

bool RegressResult::failed() const {
  return std::any_of(changes.begin(), changes.end(), [](const Change& c) { return c.regression; });
}

RegressResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current,
                              const RegressOptions& options) {
  if (!(options.time_tolerance > 1)) throw UsageError("--time-tolerance must be greater than 1");
  if (!(options.time_floor_seconds >= 0)) throw UsageError("--time-floor must be at least 0");
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
  out << "regress: " << result.runs_compared << " runs, " << result.values_compared << " values, "
      << result.timings_compared << " timings compared (" << result.timings_below_floor << " below the noise floor); "
      << (result.failed() ? "REGRESSION" : "no regression") << "\n";
}

}  // namespace bsp::sweep
