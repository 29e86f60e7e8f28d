#include "experiments/timing.h"

#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

#include "common/cpu_time.h"
#include "common/errors.h"
#include "metrics/statistics.h"

namespace bsp::experiments {

namespace {

// Spins until this thread has used `seconds` of CPU since `start` (the planted slowdown).
void burn_until(double start, double seconds) {
  volatile double sink = 0;
  while (thread_cpu_seconds() - start < seconds) sink = sink + 1;
}

// Runs `work` until this thread has used kMinBatchSeconds of CPU since `start`; returns the runs.
std::uint64_t repeat_for_batch(const std::function<void()>& work, double start) {
  std::uint64_t runs = 0;
  do {
    work();
    ++runs;
  } while (thread_cpu_seconds() - start < kMinBatchSeconds);
  return runs;
}

}  // namespace

const TimingField* find_timing_field(std::span<const TimingField> fields, std::string_view name) {
  for (const auto& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

std::string_view timing_field_name(std::span<const TimingField> fields, TimingRole role) {
  for (const auto& f : fields)
    if (f.role == role) return f.name;
  return {};
}

void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix,
                   std::span<const TimingField> fields) {
  for (auto it = from.begin(); it != from.end();) {
    if (find_timing_field(fields, prefix + it.key())) {
      timings[prefix + it.key()] = it.value();
      it = from.erase(it);
    } else {
      ++it;
    }
  }
}

PlantedSlowdown parse_planted_slowdown(const std::string& text) {
  const auto colon = text.rfind(':');
  PlantedSlowdown p;
  const char* end = text.data() + text.size();
  if (colon != std::string::npos && colon > 0) {
    p.heuristic = text.substr(0, colon);
    const auto [ptr, ec] = std::from_chars(text.data() + colon + 1, end, p.factor);
    if (ec == std::errc() && ptr == end && std::isfinite(p.factor) && p.factor >= 1) return p;
  }
  throw UsageError("BSPBENCH_PLANT_SLOWDOWN wants heuristic:factor with factor >= 1, not '" + text + "'");
}

double TimedBatches::median() const { return bsp::median(samples); }

double time_batch(const std::function<void()>& work) {
  const double start = thread_cpu_seconds();
  const std::uint64_t runs = repeat_for_batch(work, start);
  return (thread_cpu_seconds() - start) / static_cast<double>(runs);
}

TimedBatches time_batches(const std::function<void()>& work, double plant, const std::function<void()>& reference) {
  TimedBatches out;
  for (int s = 0; s < kBatches; ++s) {
    if (reference) out.reference.push_back(time_batch(reference));
    const double start = thread_cpu_seconds();
    const std::uint64_t batch = repeat_for_batch(work, start);
    if (plant > 1) burn_until(start, plant * (thread_cpu_seconds() - start));
    out.samples.push_back((thread_cpu_seconds() - start) / static_cast<double>(batch));
    out.runs += batch;
  }
  return out;
}

}  // namespace bsp::experiments
