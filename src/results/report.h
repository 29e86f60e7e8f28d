#pragma once
// The sweep report: one versioned JSON document (analysis/SCHEMA.md) holding the suite's identity,
// one section per shard that produced it (environment, calibration), every run record, the jobs
// that failed, aggregates over seeds and a summary. Sweeps, merges and the regression gate all read
// and write it through here.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace bsp::results {

inline constexpr std::string_view kReportSchema = "bspbench-report";
// Bump on any change a reader must know about; readers reject other versions.
inline constexpr int kReportVersion = 5;

// `suite`: {name, definition_hash, jobs}. Sorts runs and failures by key and adds aggregates
// (aggregate.h) and the summary.
nlohmann::json assemble_report(nlohmann::json suite, nlohmann::json shards, nlohmann::json runs,
                               nlohmann::json failures);

// Throws InputError naming the file when it is unreadable, not JSON, not a bspbench report or of
// another version.
nlohmann::json read_report(const std::string& path);
// Creates the parent directory; the file appears whole or not at all (write_file_atomically).
void write_report(const std::string& path, const nlohmann::json& report);

}  // namespace bsp::results
