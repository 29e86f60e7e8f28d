#include "sweep/aggregate.h"

#include <array>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "metrics/statistics.h"

namespace bsp::sweep {

namespace {

// What the growth fits are taken of: for drawing runs fragments, nodes and build time, both the CPU
// time (steady on a busy machine) and the builder's wall time; for merge runs the result's size
// before and after reduction, the nodes partitioning visits, and merge time.
constexpr std::array<std::string_view, 2> kGrowthMetrics = {"fragments", "nodes"};
constexpr std::array<std::string_view, 2> kGrowthTimings = {"build_cpu_seconds", "build_seconds"};
constexpr std::array<std::string_view, 3> kMergeGrowthMetrics = {"before_nodes", "after_nodes", "partition_nodes"};
constexpr std::array<std::string_view, 2> kMergeGrowthTimings = {"merge_cpu_seconds", "merge_seconds"};
// Animate runs: the tree's size at the last frame and the update time; occlude runs: what culling
// emits, the beam's size and the culling time.
constexpr std::array<std::string_view, 2> kAnimateGrowthMetrics = {"fragments_last", "work_nodes_built"};
constexpr std::array<std::string_view, 1> kAnimateGrowthTimings = {"update_cpu_seconds"};
constexpr std::array<std::string_view, 3> kOccludeGrowthMetrics = {"emitted", "seen_by_embree", "beam_nodes"};
constexpr std::array<std::string_view, 1> kOccludeGrowthTimings = {"occlude_cpu_seconds"};
// Drawing runs also get fits over the sizes' geometric means, with intervals, of what the report's
// theory check compares with the bounds: splits (what a partition adds), fragments and build time.
constexpr std::array<std::string_view, 2> kSizeGrowthMetrics = {"splits", "fragments"};
constexpr std::array<std::string_view, 1> kSizeGrowthTimings = {"build_cpu_seconds"};
// Doom runs pool an IWAD's maps (all at n = 0): the fits say how the nodes and the build time grow
// with the map's linedef sides (n_polygons), ours and the external builders' alike.
constexpr std::array<std::string_view, 3> kDoomGrowthMetrics = {"segs", "splits", "nodes"};
constexpr std::array<std::string_view, 2> kDoomGrowthTimings = {"doom_cpu_seconds", "builder_cpu_seconds"};

struct Group {
  nlohmann::json head;                                      // scene, heuristic, shape, scene_params
  std::map<std::uint64_t, std::vector<const nlohmann::json*>> by_n;
};

bool is_merge(const nlohmann::json& head) { return head.value("kind", "") == "merge"; }

nlohmann::json group_head(const nlohmann::json& id) {
  nlohmann::json other = id["scene_params"];
  other.erase("n");
  other.erase("seed");
  nlohmann::json head{{"kind", id.value("kind", "draw")},
                      {"scene", id["scene"]},
                      {"heuristic", id["heuristic"]},
                      {"shape", id["shape"]},
                      {"scene_params", other},
                      {"constant_density", id.value("constant_density", false)}};
  if (is_merge(head)) head["operation"] = id["operation"];
  if (head["kind"] == "animate")
    for (const char* k : {"strategy", "object_heuristic", "moving", "speed", "frames", "object", "object_n", "size", "spin"})
      head[k] = id[k];
  if (head["kind"] == "doom") head["builder_kind"] = id["builder_kind"];
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

template <std::size_t K>
nlohmann::json growth_section(const Group& g, const char* section, const std::array<std::string_view, K>& fields,
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
  if (is_merge(g.head)) {
    out["growth"] = growth_section(g, "metrics", kMergeGrowthMetrics);
    out["timing_growth"] = growth_section(g, "timings", kMergeGrowthTimings);
    return out;
  }
  if (g.head["kind"] == "animate") {
    out["growth"] = growth_section(g, "metrics", kAnimateGrowthMetrics);
    out["timing_growth"] = growth_section(g, "timings", kAnimateGrowthTimings);
    return out;
  }
  if (g.head["kind"] == "occlude") {
    out["growth"] = growth_section(g, "metrics", kOccludeGrowthMetrics);
    out["timing_growth"] = growth_section(g, "timings", kOccludeGrowthTimings);
    return out;
  }
  if (g.head["kind"] == "doom") {
    out["growth"] = growth_section(g, "metrics", kDoomGrowthMetrics);
    out["timing_growth"] = growth_section(g, "timings", kDoomGrowthTimings);
    return out;
  }
  out["growth"] = growth_section(g, "metrics", kGrowthMetrics);
  out["timing_growth"] = growth_section(g, "timings", kGrowthTimings);
  // Build time against the fragments made: the heuristic's cost per unit of output, which the
  // scene's density does not change.
  out["timing_growth_vs_fragments"] = {{"build_cpu_seconds", growth(g, "timings", "build_cpu_seconds", true)}};
  // The same section names inside as outside, so deterministic_view (record.h) drops the timing fits
  // here as it drops timing_growth at every depth.
  out["growth_over_sizes"] = {{"growth", growth_section(g, "metrics", kSizeGrowthMetrics, true)},
                              {"timing_growth", growth_section(g, "timings", kSizeGrowthTimings, true)}};
  return out;
}

}  // namespace

nlohmann::json aggregate_runs(const nlohmann::json& runs) {
  // Key order makes every floating-point sum independent of the order runs finished in.
  std::map<std::string, const nlohmann::json*> by_key;
  for (const auto& r : runs) by_key[r["key"].get<std::string>()] = &r;
  std::map<std::string, Group> groups;
  for (const auto& [key, r] : by_key) {
    nlohmann::json head = group_head((*r)["id"]);
    Group& g = groups[head.dump()];
    g.head = std::move(head);
    g.by_n[(*r)["id"]["n"].get<std::uint64_t>()].push_back(r);
  }
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [key, g] : groups) out.push_back(group_json(g));
  return out;
}

}  // namespace bsp::sweep
