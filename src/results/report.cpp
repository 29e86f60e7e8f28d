#include "results/report.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "results/aggregate.h"
#include "results/record.h"

namespace bsp::results {

namespace {

void sort_by_key(nlohmann::json& records) {
  std::sort(records.begin(), records.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a["key"] < b["key"]; });
}

// The count summed over the runs whose violations are ours (`judged`), or over the others.
std::uint64_t sum_counts(const nlohmann::json& runs, const char* section, const char* field = "violations",
                         bool judged = true) {
  std::uint64_t total = 0;
  for (const auto& r : runs)
    if (r.contains(section) && r[section].is_object() &&
        judged_for_violations(r.value("id", nlohmann::json::object())) == judged)
      total += r[section].value(field, std::uint64_t{0});
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
          {"others_violations", sum_counts(runs, "invariants", "violations", false)},
          {"complete", runs.size() + failures.size() == assigned && assigned == suite["jobs"].get<std::uint64_t>()}};
}

using JsonTest = bool (nlohmann::json::*)() const noexcept;

// `o` is an object whose member `k` passes `test` (or, with `optional`, has no member `k`).
bool has(const nlohmann::json& o, const char* k, JsonTest test, bool optional = false) {
  if (!o.is_object()) return false;
  const auto it = o.find(k);
  return it == o.end() ? optional : ((*it).*test)();
}

bool is_record(const nlohmann::json& r, std::initializer_list<const char*> objects) {
  if (!has(r, "key", &nlohmann::json::is_string)) return false;
  for (const char* k : objects)
    if (!has(r, k, &nlohmann::json::is_object)) return false;
  return true;
}

// The labels aggregation groups runs by and messages print (scene, heuristic, shape): strings,
// and present unless `optional`.
bool has_labels(const nlohmann::json& id, bool optional) {
  for (const char* k : {"scene", "heuristic", "shape"})
    if (!has(id, k, &nlohmann::json::is_string, optional)) return false;
  return true;
}

// A run of a kind this build knows, with the identity fields its kind requires
// (Kind::identity_ok: an animate run's strategy and moving count, a merge run's operation and
// two operands, a Doom run's map and builder kind).
bool has_kind(const nlohmann::json& id) {
  if (!has(id, "kind", &nlohmann::json::is_string)) return false;
  const experiments::Kind* kind = kind_of(id);
  return kind && (!kind->identity_ok || kind->identity_ok(id));
}

// What aggregation, merging and the regression gate read from a run record.
bool is_run(const nlohmann::json& r) {
  if (!is_record(r, {"id", "metrics", "invariants", "timings"}) || !r.contains("validation")) return false;
  const auto& id = r["id"];
  const auto& validation = r["validation"];
  return has_kind(id) && has(r, "calibration_seconds", &nlohmann::json::is_number) &&
         r["calibration_seconds"].get<double>() > 0 &&
         has(id, "n", &nlohmann::json::is_number_unsigned) && has(id, "n_polygons", &nlohmann::json::is_number) &&
         has(id, "scene_params", &nlohmann::json::is_object) && has_labels(id, false) &&
         has(id, "command", &nlohmann::json::is_string) &&
         has(r["invariants"], "violations", &nlohmann::json::is_number_unsigned, true) &&
         (validation.is_null() || has(validation, "violations", &nlohmann::json::is_number_unsigned, true));
}

bool is_failure(const nlohmann::json& f) {
  return is_record(f, {"id"}) && has_labels(f["id"], true) && has(f, "error", &nlohmann::json::is_string, true);
}

// The parts readers index into, so a damaged report is an InputError rather than a crash.
void check_layout(const nlohmann::json& report, const std::string& path) {
  const auto bad = [&](const std::string& what) { throw InputError(path + ": " + what); };
  const auto& suite = report["suite"];
  if (!has(suite, "name", &nlohmann::json::is_string) || !has(suite, "definition_hash", &nlohmann::json::is_string) ||
      !has(suite, "jobs", &nlohmann::json::is_number_unsigned))
    bad("\"suite\" needs name, definition_hash and jobs");
  if (!report["shards"].is_array()) bad("\"shards\" is not an array");
  for (const auto& s : report["shards"])
    if (!has(s, "index", &nlohmann::json::is_number_unsigned) || !has(s, "count", &nlohmann::json::is_number_unsigned) ||
        !has(s, "jobs", &nlohmann::json::is_number_unsigned))
      bad("a shard section lacks index, count or jobs");
  if (!report["runs"].is_array() || !report["failures"].is_array()) bad("\"runs\" and \"failures\" must be arrays");
  for (const auto& r : report["runs"])
    if (!is_run(r))
      bad("a run record lacks key, id (kind, command, scene, heuristic, shape, n, n_polygons, scene_params; a merge run's "
          "operation and two operands; an animate run's strategy, moving and speed; a Doom run's map and "
          "builder_kind), metrics, invariants, validation, timings or calibration_seconds, or one has the wrong type");
  for (const auto& f : report["failures"])
    if (!is_failure(f)) bad("a failure record lacks key or id, or one has the wrong type");
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
  if (!report.is_object() || !report.contains("schema") || report["schema"] != std::string(kReportSchema))
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

}  // namespace bsp::results
