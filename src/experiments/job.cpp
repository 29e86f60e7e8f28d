#include "experiments/job.h"

#include <chrono>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace bsp::experiments {

std::string exact_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

nlohmann::json make_record(const Job& job, nlohmann::json id, nlohmann::json metrics, nlohmann::json invariants,
                           nlohmann::json validation, nlohmann::json ray_shooting, nlohmann::json timings,
                           double start_seconds) {
  timings["job_seconds"] = wall_seconds() - start_seconds;
  return {{"key", job.key()},
          {"id", std::move(id)},
          {"metrics", std::move(metrics)},
          {"invariants", std::move(invariants)},
          {"validation", std::move(validation)},
          {"ray_shooting", std::move(ray_shooting)},
          {"timings", std::move(timings)}};
}

void pick_fields(const nlohmann::json& from, std::span<const JsonField> fields, nlohmann::json& out) {
  for (const auto& f : fields) out[f.name] = from.at(nlohmann::json::json_pointer(f.pointer));
}

}  // namespace bsp::experiments
