#pragma once
// The timings of a run record, and how runs time their work.
//
// A kind declares its timing fields once (TimingField, in its own module); the record's "timings"
// holds exactly those, split_timings() moves exactly those out of the other sections, and the
// regression gate compares exactly the kind's GatedSamples field. Everything else in a record is a
// deterministic function of the job, identical on any machine, thread count and shard, and compared
// exactly: renaming a timing without declaring it makes the gate fail loudly instead of silently
// moving the field between the two comparisons.
//
// Timed batches. The gate compares CPU times statistically, so a run times its work beyond the
// first (the result that is measured, which also warms the caches): kBatches batches, each repeating
// the work until at least kMinBatchSeconds of thread CPU time have passed. A sample is a batch's CPU
// time divided by its repetitions: the time per run over at least 2 ms, a thousand times the
// scheduler's accounting granularity, so 0.05 ms builds are measurable too. Thread CPU time, not wall
// time: on a shared machine the wall time measures the other users as much as the code.
//
// The in-run reference. Thread CPU time is not enough on a virtual machine: the same build of the
// same input, in one process, runs at one speed for a while and then about 1.6 times slower for a
// while (the cause lies with the host; the guest has no performance counters to tell), while a
// small sort-and-square-root kernel beside it moves by 10%, so one calibration per sweep cannot
// follow it (docs/results/gate-timing.md). Bias from a state of the machine that the experimenter
// neither controls nor sees is common [Mytkowicz2009]. So each batch is preceded by a batch of a
// reference: fixed code of the same character on the job's own input (Embree's BVH build,
// reference_build.h), timed the same way. A state that slows the work slows the reference timed
// milliseconds before it, and the gate divides each sample by its batch's reference.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace bsp::experiments {

enum class TimingRole {
  Wall,            // wall-clock seconds: reported, not gated (on a shared machine they measure the others)
  Rate,            // per wall-clock second: reported, not gated
  Cpu,             // thread CPU seconds of one measurement: reported, not gated
  GatedSamples,    // thread CPU seconds per run of the work, one per timed batch: what the gate compares
  ReferenceSamples,  // thread CPU seconds per run of the in-run reference, one per batch, paired with
                     // the gated samples: the gate compares their ratios
  SamplesMedian,   // the median of the gated samples, for reports and growth fits
  SampleCount,     // runs timed for the samples: depends on the machine's speed, so not deterministic
  UngatedSamples,  // samples of work that is not ours (an external tool): reported, not gated
};

struct TimingField {
  std::string_view name;  // as stored in a run's "timings"
  TimingRole role;
  std::string_view meaning;
};

// The field of `fields` with `name`; nullptr when there is none.
const TimingField* find_timing_field(std::span<const TimingField> fields, std::string_view name);
// The name of the first field of `role`; empty when there is none.
std::string_view timing_field_name(std::span<const TimingField> fields, TimingRole role);

// Moves the fields of the flat object `from` whose prefixed names are declared in `fields` into
// `timings`, under their prefixed names.
void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix,
                   std::span<const TimingField> fields);

inline constexpr int kBatches = 5;
inline constexpr double kMinBatchSeconds = 0.002;

// TEST ONLY: makes every timed batch of the runs of one heuristic label cost `factor` times its CPU
// time, by burning (factor - 1) times the batch's CPU time inside the timed region, so tests can
// show that the gate catches a slowdown. Set through the BSPBENCH_PLANT_SLOWDOWN environment
// variable of `bspbench sweep` (heuristic:factor, e.g. naylor:1.5); never in a baseline. A report
// made with it names it in its shard section ("planted_slowdown").
struct PlantedSlowdown {
  std::string heuristic;
  double factor = 1;  // >= 1
};
// Parses "heuristic:factor"; throws UsageError naming the variable.
PlantedSlowdown parse_planted_slowdown(const std::string& text);

struct TimedBatches {
  std::vector<double> samples;    // CPU seconds per run of the work, one per batch
  std::vector<double> reference;  // CPU seconds per run of the reference, one per batch; empty without one
  std::uint64_t runs = 0;         // runs timed in all
  double median() const;
};
// kBatches batches of `work` (see the header comment), each slowed by `plant` when it is above 1,
// and each preceded by a batch of `reference` when there is one.
TimedBatches time_batches(const std::function<void()>& work, double plant = 1.0,
                          const std::function<void()>& reference = {});
// CPU seconds per run of `work`, repeated until at least kMinBatchSeconds have passed: one batch.
double time_batch(const std::function<void()>& work);

}  // namespace bsp::experiments
