#include "sweep/record.h"

#include <array>

namespace bsp::sweep {

namespace {

constexpr std::array<std::string_view, 4> kNonDeterministicKeys = {"shards", "timings", "timing_growth",
                                                                   "calibration_seconds"};

bool non_deterministic(const std::string& key) {
  for (auto k : kNonDeterministicKeys)
    if (key == k) return true;
  return false;
}

}  // namespace

bool is_timing_field(std::string_view name) {
  return name == "seconds" || name.ends_with("_seconds") || name.ends_with("_per_second");
}

void split_timings(nlohmann::json& from, nlohmann::json& timings, const std::string& prefix) {
  for (auto it = from.begin(); it != from.end();) {
    if (is_timing_field(it.key())) {
      timings[prefix + it.key()] = it.value();
      it = from.erase(it);
    } else {
      ++it;
    }
  }
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
