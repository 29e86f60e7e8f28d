#pragma once
// The layout of a run record, and which of its numbers are timings.
//
// A run record (analysis/SCHEMA.md) is {key, id, metrics, invariants, validation, ray_shooting,
// timings, calibration_seconds}, and a Doom run's `error` when its external builder failed. The
// timing fields are declared in ONE place, timing_fields(): split_timings() moves exactly those out
// of the metrics and validation objects into "timings", and the regression gate gates exactly the
// ones declared as build samples (drawing runs), merge samples (merge runs), update samples
// (animate runs), occlude samples (occlude runs) and Doom samples (Doom runs of our heuristics).
// Everything else in a record is a deterministic function of the job — identical on any machine,
// thread count and shard — and compared exactly by the gate. A field that is not declared stays
// where it is and is compared exactly, whatever its name: renaming a timing without declaring it
// makes the gate fail loudly instead of silently moving the field between the two comparisons.
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace bsp::sweep {

enum class TimingKind {
  Wall,          // wall-clock seconds: reported, not gated (on a shared machine they measure the others)
  Rate,          // per wall-clock second: reported, not gated
  Cpu,           // thread CPU seconds of one measurement: reported, not gated
  BuildSamples,  // thread CPU seconds per build, one per timed batch: what the gate compares
  BuildSummary,  // the median of the build samples, for reports and growth fits
  BuildCount,    // builds timed for the samples: depends on the machine's speed, so not deterministic
  MergeSamples,  // thread CPU seconds per merge, one per timed batch: what the gate compares for merges
  MergeSummary,  // the median of the merge samples
  MergeCount,    // merges timed for the samples
  UpdateSamples, // thread CPU seconds of each frame's update: what the gate compares for animate runs
  UpdateSummary, // the median of the update samples
  OccludeSamples,  // thread CPU seconds per culling of every view, one per timed batch: gated for occlude runs
  OccludeSummary,  // the median of the occlude samples, per view
  OccludeCount,    // cullings of every view timed for the samples
  DoomSamples,     // thread CPU seconds per build of a Doom map's nodes by our heuristic, one per timed batch: gated
  DoomSummary,     // the median of the Doom samples
  DoomCount,       // builds timed for the Doom samples
  BuilderSamples,  // an external node builder's CPU seconds per run: reported, not gated (not our code)
};

struct TimingField {
  std::string_view name;  // as stored in a run's "timings"
  TimingKind kind;
  std::string_view meaning;
};

// Every timing field of a run record.
std::span<const TimingField> timing_fields();
// nullptr when `name` is not a declared timing field.
const TimingField* find_timing_field(std::string_view name);
// The declared field of this kind (there is one each of the Build, Merge, Update, Occlude and Doom kinds).
std::string_view timing_field_name(TimingKind kind);

// Moves the fields of the flat object `from` whose prefixed names are declared timing fields into
// `timings`, under their prefixed names.
void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix);

// Whether the run's violations are ours to answer for: false only for a Doom run of nodes made by
// others (an external builder or the WAD's shipped nodes), whose violations are facts about them,
// reported but never failed. `id` is the run's identity.
bool judged_for_violations(const nlohmann::json& id);

// The report without anything that depends on when, where or how fast it ran: shard sections,
// environments, calibrations and timings (the keys "shards", "timings", "timing_growth",
// "timing_growth_vs_fragments" and "calibration_seconds" at any depth). Two sweeps of one suite agree on it exactly.
nlohmann::json deterministic_view(const nlohmann::json& report);

}  // namespace bsp::sweep
