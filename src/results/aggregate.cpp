#include "results/aggregate.h"

#include <cmath>
#include <span>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "metrics/statistics.h"
#include "results/record.h"

namespace bsp::results {

namespace {

struct Group {
  const experiments::Kind* kind = nullptr;
  nlohmann::json head;                                      // kind, scene, heuristic, shape, scene_params, the kind's group_by
  std::map<std::uint64_t, std::vector<const nlohmann::json*>> by_n;
};

// The kind's fields that group runs (experiments/kind.h) beside the ones every kind has.
nlohmann::json group_head(const nlohmann::json& id, const experiments::Kind& kind) {
  nlohmann::json other = id["scene_params"];
  other.erase("n");
  other.erase("seed");
  nlohmann::json head{{"kind", id.value("kind", "draw")},
                      {"scene", id["scene"]},
                      {"heuristic", id["heuristic"]},
                      {"shape", id["shape"]},
                      {"scene_params", other},
                      {"constant_density", id.value("constant_density", false)}};
  // A field a run leaves out is left out of its group's head (a merge run's kernel, float unless named).
  for (const auto field : kind.group_by)
    if (id.contains(std::string(field))) head[std::string(field)] = id[std::string(field)];
  return head;
}

// Summary of every numeric field of `section` over the runs.
nlohmann::json summarize_section(const std::vector<const nlohmann::json*>& runs, const char* section) {
  std::map<std::string, std::vector<double>> samples;
  for (const auto* r : runs)
    for (const auto& [k, v] : (*r)[section].items())
      if (v.is_number()) samples[k].push_back(v.get<double>());
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [k, xs] : samples) out[k] = to_json(summarize(xs));
  return out;
}

std::uint64_t validation_violations(const std::vector<const nlohmann::json*>& runs) {
  std::uint64_t total = 0;
  for (const auto* r : runs) {
    const auto& v = (*r)["validation"];
    if (v.is_object()) total += v.value("violations", std::uint64_t{0});
  }
  return total;
}

nlohmann::json size_entry(std::uint64_t n, const std::vector<const nlohmann::json*>& runs) {
  std::vector<double> polys;
  for (const auto* r : runs) polys.push_back((*r)["id"]["n_polygons"].get<double>());
  return {{"n", n},
          {"runs", runs.size()},
          {"n_polygons", to_json(summarize(polys))},
          {"metrics", summarize_section(runs, "metrics")},
          {"validation_violations", validation_violations(runs)},
          {"timings", summarize_section(runs, "timings")}};
}

// The run's polygon count, or with `against_fragments` the fragments its tree holds.
double growth_x(const nlohmann::json& run, bool against_fragments) {
  return against_fragments ? run["metrics"].value("fragments", 0.0) : run["id"]["n_polygons"].get<double>();
}

nlohmann::json growth(const Group& g, const char* section, std::string_view field, bool against_fragments = false) {
  std::vector<double> x, y;
  for (const auto& [n, runs] : g.by_n)
    for (const auto* r : runs) {
      const auto& v = (*r)[section];
      if (!v.contains(field) || !v[std::string(field)].is_number()) continue;
      x.push_back(growth_x(*r, against_fragments));
      y.push_back(v[std::string(field)].get<double>());
    }
  try {
    nlohmann::json fit = to_json(fit_power_law(x, y));
    fit["points"] = x.size();
    return fit;
  } catch (const std::invalid_argument&) {
    return nullptr;  // fewer than two sizes, or a zero value: no power law to fit
  }
}

// Each size's geometric means of polygon count and value over its seeds with a positive value (a
// size without one drops out).
std::pair<std::vector<double>, std::vector<double>> size_means(const Group& g, const char* section,
                                                               std::string_view field) {
  std::vector<double> x, y;
  for (const auto& [n, runs] : g.by_n) {
    double log_x = 0, log_y = 0, count = 0;
    for (const auto* r : runs) {
      const auto& v = (*r)[section];
      const double polygons = (*r)["id"]["n_polygons"].get<double>();
      if (!v.contains(field) || !v[std::string(field)].is_number() || !(polygons > 0)) continue;
      const double value = v[std::string(field)].get<double>();
      if (!(value > 0)) continue;
      log_x += std::log(polygons);
      log_y += std::log(value);
      ++count;
    }
    if (count == 0) continue;
    x.push_back(std::exp(log_x / count));
    y.push_back(std::exp(log_y / count));
  }
  return {x, y};
}

// The fit through one point per size. Seeds are replicates of one size, not independent points of
// the curve: pooling them would shrink the interval with every seed added. Null with fewer than
// three sizes, where no interval exists.
nlohmann::json growth_over_sizes(const Group& g, const char* section, std::string_view field) {
  const auto [x, y] = size_means(g, section, field);
  if (x.size() < 3) return nullptr;
  try {
    const PowerFit f = fit_power_law(x, y);
    return {{"exponent", f.exponent},
            {"ci95", {f.exponent - f.half_width, f.exponent + f.half_width}},
            {"r2", f.r2},
            {"sizes", f.points}};
  } catch (const std::invalid_argument&) {
    return nullptr;  // every size has the same polygon count
  }
}

nlohmann::json growth_section(const Group& g, const char* section, std::span<const std::string_view> fields,
                              bool over_sizes = false) {
  nlohmann::json out = nlohmann::json::object();
  for (auto f : fields) out[std::string(f)] = over_sizes ? growth_over_sizes(g, section, f) : growth(g, section, f);
  return out;
}

nlohmann::json group_json(const Group& g) {
  nlohmann::json out = g.head;
  nlohmann::json sizes = nlohmann::json::array();
  for (const auto& [n, runs] : g.by_n) sizes.push_back(size_entry(n, runs));
  out["by_n"] = std::move(sizes);
  out["growth"] = growth_section(g, "metrics", g.kind->growth_metrics);
  out["timing_growth"] = growth_section(g, "timings", g.kind->growth_timings);
  if (const auto f = g.kind->growth_against_fragments; !f.empty())
    out["timing_growth_vs_fragments"] = {{std::string(f), growth(g, "timings", f, true)}};
  // The same section names inside as outside, so deterministic_view (record.h) drops the timing fits
  // here as it drops timing_growth at every depth.
  if (!g.kind->size_growth_metrics.empty() || !g.kind->size_growth_timings.empty())
    out["growth_over_sizes"] = {{"growth", growth_section(g, "metrics", g.kind->size_growth_metrics, true)},
                                {"timing_growth", growth_section(g, "timings", g.kind->size_growth_timings, true)}};
  return out;
}

}  // namespace

nlohmann::json aggregate_runs(const nlohmann::json& runs) {
  // Key order makes every floating-point sum independent of the order runs finished in.
  std::map<std::string, const nlohmann::json*> by_key;
  for (const auto& r : runs) by_key[r["key"].get<std::string>()] = &r;
  std::map<std::string, Group> groups;
  for (const auto& [key, r] : by_key) {
    const experiments::Kind* kind = kind_of((*r)["id"]);
    if (!kind) throw InputError("run " + key + ": unknown kind " + (*r)["id"]["kind"].dump());
    nlohmann::json head = group_head((*r)["id"], *kind);
    Group& g = groups[head.dump()];
    g.kind = kind;
    g.head = std::move(head);
    g.by_n[(*r)["id"]["n"].get<std::uint64_t>()].push_back(r);
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [key, g] : groups) out.push_back(group_json(g));
  return out;
}

}  // namespace bsp::results
