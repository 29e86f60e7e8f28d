#pragma once
// The layout of a run record, and which of its numbers are deterministic.
//
// A run record (analysis/SCHEMA.md) is {key, id, metrics, invariants, validation, timings,
// calibration_seconds}. Timings are the fields named "seconds" or ending in "_seconds" or
// "_per_second": split_timings() moves them out of the metrics and validation objects into
// "timings", so everything else in a record is a deterministic function of the job — identical on
// any machine, thread count and shard — and compared exactly by the regression gate.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace bsp::sweep {

bool is_timing_field(std::string_view name);

// Moves the timing fields of the flat object `from` into `timings`, their names prefixed by `prefix`.
void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix);

// The report without anything that depends on when, where or how fast it ran: shard sections,
// environments, calibrations and timings (the keys "shards", "timings", "timing_growth" and
// "calibration_seconds" at any depth). Two sweeps of one suite agree on it exactly.
nlohmann::json deterministic_view(const nlohmann::json& report);

}  // namespace bsp::sweep
