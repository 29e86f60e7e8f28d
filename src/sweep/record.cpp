#include "sweep/record.h"

#include <array>

namespace bsp::sweep {

namespace {

constexpr std::array<std::string_view, 5> kNonDeterministicKeys = {"shards", "timings", "timing_growth",
                                                                   "timing_growth_vs_fragments", "calibration_seconds"};

bool non_deterministic(const std::string& key) {
  for (auto k : kNonDeterministicKeys)
    if (key == k) return true;
  return false;
}

constexpr TimingField kTimingFields[] = {
    {"build_seconds", TimingKind::Wall, "wall time of the first build (the tree that is measured)"},
    {"build_cpu_samples", TimingKind::BuildSamples,
     "thread CPU seconds per build, one per timed batch of at least 2 ms (run_job.h)"},
    {"build_cpu_seconds", TimingKind::BuildSummary, "the median of build_cpu_samples"},
    {"build_cpu_builds", TimingKind::BuildCount, "builds timed for the samples: depends on the machine's speed"},
    {"metrics_cpu_seconds", TimingKind::Cpu, "thread CPU seconds of measure_tree"},
    {"validation_seconds", TimingKind::Wall, "wall time of the Embree order check"},
    {"validation_rays_per_second", TimingKind::Rate, "rays cast per wall-clock second in the order check"},
    {"job_seconds", TimingKind::Wall, "wall time of the whole job"},
    {"merge_cpu_samples", TimingKind::MergeSamples,
     "thread CPU seconds per merge (merge and reduce), one per timed batch of at least 2 ms (run_merge_job.h)"},
    {"merge_cpu_seconds", TimingKind::MergeSummary, "the median of merge_cpu_samples"},
    {"merge_cpu_merges", TimingKind::MergeCount, "merges timed for the samples: depends on the machine's speed"},
    {"merge_seconds", TimingKind::Wall, "wall time of the first merge (the result that is checked), reduction excluded"},
    {"reduce_seconds", TimingKind::Wall, "wall time of the first merge's reduction"},
    {"build_a_cpu_seconds", TimingKind::Cpu, "thread CPU seconds of the first operand's solid tree (build and labels)"},
    {"build_b_cpu_seconds", TimingKind::Cpu, "thread CPU seconds of the second operand's solid tree"},
    {"corefine_seconds", TimingKind::Wall, "wall time of CGAL's corefinement of the same operands (the reference)"},
    {"check_seconds", TimingKind::Wall, "wall time of the proof against CGAL (points, volume, boundary)"},
    {"update_cpu_samples", TimingKind::UpdateSamples,
     "thread CPU seconds of each frame's update, frames 1 on (animate runs: run_dynamic_jobs.h)"},
    {"update_cpu_seconds", TimingKind::UpdateSummary, "the median of update_cpu_samples"},
    {"update_cpu_seconds_max", TimingKind::Cpu, "the slowest update"},
    {"start_cpu_seconds", TimingKind::Cpu, "thread CPU seconds of the strategy's first frame (its whole build)"},
    {"occlude_cpu_samples", TimingKind::OccludeSamples,
     "thread CPU seconds per culling of every view, one per timed batch of at least 2 ms (occlude runs)"},
    {"occlude_cpu_seconds", TimingKind::OccludeSummary, "the median of occlude_cpu_samples, divided by the views"},
    {"occlude_cpu_runs", TimingKind::OccludeCount, "cullings of every view timed: depends on the machine's speed"},
    {"occluder_setup_cpu_seconds", TimingKind::Cpu, "thread CPU seconds of the subtree boxes (once per tree)"},
    {"doom_cpu_samples", TimingKind::DoomSamples,
     "thread CPU seconds per build of a Doom map's nodes (leafy tree and vanilla lumps), one per timed batch of at "
     "least 2 ms (Doom runs of our heuristics: run_doom_job.h)"},
    {"doom_cpu_seconds", TimingKind::DoomSummary, "the median of doom_cpu_samples"},
    {"doom_cpu_runs", TimingKind::DoomCount, "builds timed for the samples: depends on the machine's speed"},
    {"builder_cpu_samples", TimingKind::BuilderSamples,
     "an external node builder's CPU seconds (user + system of its process) in each of 5 runs; not gated"},
    {"builder_cpu_seconds", TimingKind::Cpu, "the median of builder_cpu_samples"},
};

}  // namespace

std::span<const TimingField> timing_fields() { return kTimingFields; }

const TimingField* find_timing_field(std::string_view name) {
  for (const auto& f : kTimingFields)
    if (f.name == name) return &f;
  return nullptr;
}

std::string_view timing_field_name(TimingKind kind) {
  for (const auto& f : kTimingFields)
    if (f.kind == kind) return f.name;
  return {};
}

void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix) {
  for (auto it = from.begin(); it != from.end();) {
    if (find_timing_field(prefix + it.key())) {
      timings[prefix + it.key()] = it.value();
      it = from.erase(it);
    } else {
      ++it;
    }
  }
}

bool judged_for_violations(const nlohmann::json& id) {
  return !id.is_object() || id.value("kind", "") != "doom" || id.value("builder_kind", "") == "heuristic";
}

nlohmann::json deterministic_view(const nlohmann::json& report) {
  if (report.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : report) out.push_back(deterministic_view(v));
    return out;
  }
  if (!report.is_object()) return report;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [k, v] : report.items())
    if (!non_deterministic(k)) out[k] = deterministic_view(v);
  return out;
}

}  // namespace bsp::sweep
