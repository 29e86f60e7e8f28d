#include "results/record.h"

#include <array>

#include "kinds/kinds.h"

namespace bsp::results {

namespace {

constexpr std::array<std::string_view, 5> kNonDeterministicKeys = {"shards", "timings", "timing_growth",
                                                                   "timing_growth_vs_fragments", "calibration_seconds"};

bool non_deterministic(const std::string& key) {
  for (auto k : kNonDeterministicKeys)
    if (key == k) return true;
  return false;
}

}  // namespace

const experiments::Kind* kind_of(const nlohmann::json& id) {
  if (!id.is_object() || !id.contains("kind")) return find_kind("draw");
  const auto& kind = id["kind"];
  return kind.is_string() ? find_kind(kind.get<std::string>()) : nullptr;
}

const experiments::TimingField* find_timing_field(const nlohmann::json& id, std::string_view name) {
  const experiments::Kind* kind = kind_of(id);
  return kind ? experiments::find_timing_field(kind->timings, name) : nullptr;
}

std::string_view timing_of_role(const nlohmann::json& id, experiments::TimingRole role) {
  const experiments::Kind* kind = kind_of(id);
  return kind ? experiments::timing_field_name(kind->timings, role) : std::string_view{};
}

bool judged_for_violations(const nlohmann::json& id) {
  const experiments::Kind* kind = kind_of(id);
  return !kind || !kind->judged_for_violations || kind->judged_for_violations(id);
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

}  // namespace bsp::results
