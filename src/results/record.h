#pragma once
// Reading run records (analysis/SCHEMA.md) as the results and the gate need them. A record is
// {key, id, metrics, invariants, validation, ray_shooting, timings, calibration_seconds}, and a
// Doom run's `error` when its external builder failed. Its kind (id.kind) says which timing fields
// it declares (experiments/kind.h): those are timings, everything else in it is a deterministic
// function of the job, identical on any machine, thread count and shard.
#include <string_view>

#include <nlohmann/json.hpp>

#include "experiments/kind.h"

namespace bsp::results {

// The kind of a record's id ("draw" when it names none, as the first reports did); nullptr for a
// kind this build does not know.
const experiments::Kind* kind_of(const nlohmann::json& id);

// The field of the record's kind declared as `name` in its timings; nullptr when there is none.
const experiments::TimingField* find_timing_field(const nlohmann::json& id, std::string_view name);

// The name of this record's kind's first timing of `role` (TimingRole::GatedSamples: the timing the
// gate compares; ReferenceSamples: what it compares them against); empty when it has none.
std::string_view timing_of_role(const nlohmann::json& id, experiments::TimingRole role);

// Whether the run's violations are ours to answer for (Kind::judged_for_violations).
bool judged_for_violations(const nlohmann::json& id);

// The report without anything that depends on when, where or how fast it ran: shard sections,
// environments, calibrations and timings (the keys "shards", "timings", "timing_growth",
// "timing_growth_vs_fragments" and "calibration_seconds" at any depth). Two sweeps of one suite agree on it exactly.
nlohmann::json deterministic_view(const nlohmann::json& report);

}  // namespace bsp::results
