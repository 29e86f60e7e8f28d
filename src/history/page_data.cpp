#include "history/page_data.h"

#include <cmath>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "common/errors.h"
#include "gate/regress.h"
#include "metrics/statistics.h"

namespace bsp::history {

namespace {

// One entry's values per group: timing, and the sums of the metrics.
struct GroupValues {
  double log_timing = 0;
  std::size_t timed = 0;
  std::map<std::string, double> metrics;
};

std::map<std::string, GroupValues> group_values(const nlohmann::json& report) {
  std::map<std::string, GroupValues> out;
  for (const auto& run : report["runs"]) {
    const gate::RunTiming t = gate::run_timing(run);
    GroupValues& g = out[t.group];
    if (const double m = t.samples.empty() ? 0.0 : median(t.samples); m > 0) {
      g.log_timing += std::log(m);
      ++g.timed;
    }
    if (!run.contains("metrics") || !run["metrics"].is_object()) continue;
    for (const auto& [k, v] : run["metrics"].items())
      if (v.is_number()) g.metrics[k] += v.get<double>();
  }
  return out;
}

// The gate's decision on `report` against the pooled `earlier` reports (none: not judged).
nlohmann::json decision(const std::deque<nlohmann::json>& earlier, const nlohmann::json& report,
                        const std::vector<std::int64_t>& against) {
  if (earlier.empty()) return {{"judged", false}};
  std::vector<const nlohmann::json*> reports;
  for (const nlohmann::json& e : earlier) reports.push_back(&e);
  const gate::RegressResult r = gate::compare_reports(gate::pool_reports(reports), report, gate::RegressOptions{});
  std::set<std::string> slower;
  std::size_t regressions = 0;
  for (const gate::Change& c : r.changes) {
    regressions += c.regression;
    if (c.regression && c.what == "slower") slower.insert(c.run);
  }
  return {{"judged", true}, {"against", against}, {"failed", r.failed()}, {"regressions", regressions},
          {"slower", slower}};
}

nlohmann::json suite_data(const Database& db, const std::string& suite, const PageSettings& settings) {
  const std::size_t last = settings.last;
  const std::vector<Entry> entries = db.entries(suite);
  nlohmann::json out{{"name", suite}, {"entries", nlohmann::json::array()}, {"machines", nlohmann::json::object()}};
  // label -> {timing: [{i, v}], metrics: {name: [{i, v}]}}, i the entry's index: a group absent
  // from an entry has no point there.
  std::map<std::string, nlohmann::json> groups;
  // The last k parsed reports of each machine: every report is read once.
  std::map<std::string, std::deque<nlohmann::json>> window;
  std::map<std::string, std::deque<std::int64_t>> window_ids;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    nlohmann::json report = db.report(e.id);
    auto& earlier = window[e.machine.fingerprint];
    auto& ids = window_ids[e.machine.fingerprint];
    out["entries"].push_back({{"id", e.id}, {"revision", e.revision}, {"date_utc", e.date_utc},
                              {"machine", e.machine.fingerprint}, {"calibration_seconds", e.calibration_seconds},
                              {"runs", e.runs}, {"failures", e.failures},
                              {"gate", decision(earlier, report, {ids.begin(), ids.end()})}});
    out["machines"][e.machine.fingerprint] = {{"cpu_model", e.machine.cpu_model}, {"hardware_threads", e.machine.hardware_threads},
                                              {"compiler", e.machine.compiler}, {"flags", e.machine.flags}};
    for (auto& [label, v] : group_values(report)) {
      nlohmann::json& g = groups[label];
      if (g.is_null()) g = {{"timing", nlohmann::json::array()}, {"metrics", nlohmann::json::object()}};
      if (v.timed) g["timing"].push_back({{"i", i}, {"v", std::exp(v.log_timing / static_cast<double>(v.timed))}});
      for (const auto& [k, x] : v.metrics) g["metrics"][k].push_back({{"i", i}, {"v", x}});
    }
    earlier.push_back(std::move(report));
    ids.push_back(e.id);
    if (earlier.size() > last) earlier.pop_front(), ids.pop_front();
    if (settings.on_entry) settings.on_entry(e.runs);
  }
  out["groups"] = groups;
  return out;
}

}  // namespace

nlohmann::json page_data(const Database& db, const PageSettings& settings) {
  std::set<std::string> suites;
  for (const Entry& e : db.entries(settings.suite)) suites.insert(e.suite);
  if (suites.empty())
    throw InputError(db.path() + ": no entries" + (settings.suite ? " of suite " + *settings.suite : std::string()));
  nlohmann::json out{{"database", db.path()}, {"last", settings.last}, {"suites", nlohmann::json::array()}};
  for (const std::string& s : suites) out["suites"].push_back(suite_data(db, s, settings));
  return out;
}

}  // namespace bsp::history
