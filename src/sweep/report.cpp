#include "sweep/report.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "sweep/aggregate.h"

namespace bsp::sweep {

namespace {

void sort_by_key(nlohmann::json& records) {
  std::sort(records.begin(), records.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a["key"] < b["key"]; });
}

std::uint64_t sum_counts(const nlohmann::json& runs, const char* section, const char* field = "violations") {
  std::uint64_t total = 0;
  for (const auto& r : runs)
    if (r.contains(section) && r[section].is_object()) total += r[section].value(field, std::uint64_t{0});
  return total;
}

nlohmann::json summary(const nlohmann::json& suite, const nlohmann::json& shards, const nlohmann::json& runs,
                       const nlohmann::json& failures) {
  std::uint64_t assigned = 0;
  for (const auto& s : shards) assigned += s["jobs"].get<std::uint64_t>();
  return {{"runs", runs.size()},
          {"failures", failures.size()},
          {"invariant_violations", sum_counts(runs, "invariants")},
          {"validation_violations", sum_counts(runs, "validation")},
          {"ray_shoot_mismatches", sum_counts(runs, "ray_shooting", "mismatches")},
          {"complete", runs.size() + failures.size() == assigned && assigned == suite["jobs"].get<std::uint64_t>()}};
}

bool is_record(const nlohmann::json& r, std::initializer_list<const char*> objects) {
  if (!r.is_object() || !r.contains("key") || !r["key"].is_string()) return false;
  for (const char* k : objects)
    if (!r.contains(k) || !r[k].is_object()) return false;
  return true;
}

// The parts readers index into, so a damaged report is an InputError rather than a crash.
void check_layout(const nlohmann::json& report, const std::string& path) {
  const auto bad = [&](const std::string& what) { throw InputError(path + ": " + what); };
  const auto& suite = report["suite"];
  if (!suite.is_object() || !suite.contains("name") || !suite["name"].is_string() ||
      !suite.contains("definition_hash") || !suite["definition_hash"].is_string() || !suite.contains("jobs") ||
      !suite["jobs"].is_number_unsigned())
    bad("\"suite\" needs name, definition_hash and jobs");
  if (!report["shards"].is_array()) bad("\"shards\" is not an array");
  for (const auto& s : report["shards"])
    if (!s.is_object() || !s.contains("index") || !s["index"].is_number_unsigned() || !s.contains("count") ||
        !s["count"].is_number_unsigned() || !s.contains("jobs") || !s["jobs"].is_number_unsigned())
      bad("a shard section lacks index, count or jobs");
  if (!report["runs"].is_array() || !report["failures"].is_array()) bad("\"runs\" and \"failures\" must be arrays");
  for (const auto& r : report["runs"])
    if (!is_record(r, {"id", "metrics", "invariants", "timings"}) || !r.contains("calibration_seconds") ||
        !r["calibration_seconds"].is_number() ||
        !(r["calibration_seconds"].get<double>() > 0) || !r["id"].contains("n") || !r["id"]["n"].is_number_unsigned())
      bad("a run record lacks key, id, metrics, invariants, timings or calibration_seconds");
  for (const auto& f : report["failures"])
    if (!is_record(f, {"id"})) bad("a failure record lacks key or id");
}

}  // namespace

nlohmann::json assemble_report(nlohmann::json suite, nlohmann::json shards, nlohmann::json runs,
                               nlohmann::json failures) {
  sort_by_key(runs);
  sort_by_key(failures);
  nlohmann::json report{{"schema", kReportSchema}, {"version", kReportVersion}, {"suite", std::move(suite)},
                        {"shards", std::move(shards)}};
  report["summary"] = summary(report["suite"], report["shards"], runs, failures);
  report["aggregates"] = aggregate_runs(runs);
  report["runs"] = std::move(runs);
  report["failures"] = std::move(failures);
  return report;
}

nlohmann::json read_report(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the report");
  nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (report.is_discarded()) throw InputError(path + ": not valid JSON");
  if (!report.is_object() || report.value("schema", "") != kReportSchema)
    throw InputError(path + ": not a bspbench report (no \"schema\": \"" + std::string(kReportSchema) + "\")");
  if (!report.contains("version") || !report["version"].is_number_integer() || report["version"] != kReportVersion)
    throw InputError(path + ": report version " + report["version"].dump() + ", this bspbench reads version " +
                     std::to_string(kReportVersion));
  for (const char* key : {"suite", "shards", "runs", "failures"})
    if (!report.contains(key)) throw InputError(path + ": report lacks \"" + std::string(key) + "\"");
  check_layout(report, path);
  return report;
}

void write_report(const std::string& path, const nlohmann::json& report) {
  const auto dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  write_file_atomically(path, report.dump(1) + "\n");
}

}  // namespace bsp::sweep
