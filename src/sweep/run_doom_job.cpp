#include "sweep/run_doom_job.h"

#include <chrono>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/hash.h"
#include "io/doom_map.h"
#include "io/doom_nodes.h"
#include "io/wad.h"
#include "metrics/statistics.h"
#include "sweep/doom_job.h"
#include "sweep/doom_run.h"
#include "sweep/node_builders.h"
#include "sweep/record.h"

namespace bsp::sweep {

namespace {

nlohmann::json metrics_json(const DoomRun& r) {
  nlohmann::json m{{"segs", r.stats.segs},           {"subsectors", r.stats.subsectors},
                   {"nodes", r.stats.nodes},         {"splits", r.stats.splits},
                   {"max_depth", r.stats.max_depth}, {"mean_depth", r.stats.mean_depth}};
  if (r.kind != DoomBuilder::Kind::Heuristic) return m;
  m["segments"] = r.segments;
  m["fallbacks"] = r.fallbacks;
  m["mixed_leaves"] = r.mixed_leaves;
  m["zero_length_linedefs"] = r.dropped;
  m["coincident_sides"] = r.coincident;
  m["rounding_split_vertices"] = r.rounding.split_vertices;
  m["rounding_max_shift"] = r.rounding.max_shift;
  m["rounding_mean_shift"] = r.rounding.mean_shift;
  m["rounding_collapsed_segs"] = r.rounding.collapsed_segs;
  return m;
}

nlohmann::json invariants_json(const DoomCheckReport& c) {
  return {{"violations", c.violations()},
          {"first_problems", c.first_problems},
          {"worst_side_distance", c.worst_side_distance},
          {"worst_convexity_distance", c.worst_convexity_distance}};
}

// The map's lumps as the IWAD holds them: says which map was read, whatever the IWAD's release.
std::string map_hash(const Wad& wad, const DoomMap& map) {
  Hasher h;
  h.add_string(wad_bytes(single_map_pwad(wad, map)));
  return h.hex();
}

// The segments are made once, outside the timed region, as run_doom times ours.
void time_ours(const DoomMap& map, const DoomBuilder& b, std::uint64_t seed, double plant, nlohmann::json& timings) {
  const DoomSegs segs = doom_segs(map);
  const TimedBatches batches = time_batches([&] { build_our_nodes(map, segs, b, seed); }, plant);
  timings["doom_cpu_samples"] = batches.samples;
  timings["doom_cpu_runs"] = batches.runs;
  timings["doom_cpu_seconds"] = batches.median();
}

// The first run's CPU time and kBuildSamples - 1 more runs: one process start each, so no batches.
void time_external(const std::string& path, const Wad& wad, const DoomMap& map, const DoomBuilder& b,
                   const DoomRun& first, nlohmann::json& timings) {
  std::vector<double> samples{first.cpu_seconds};
  while (samples.size() < static_cast<std::size_t>(kBuildSamples))
    samples.push_back(run_doom(path, wad, map, b, {}).cpu_seconds);
  timings["builder_cpu_samples"] = samples;
  timings["builder_cpu_seconds"] = median(samples);
}

// The sides of the map's linedefs: what every builder starts from, and what its splits are counted
// against (io/doom_tree_stats.h).
std::uint64_t linedef_sides(const DoomMap& map) {
  std::uint64_t sides = 0;
  for (const Linedef& l : map.linedefs)
    for (const auto side : l.sidenum) sides += side == kNoSidedef ? 0 : 1;
  return sides;
}

nlohmann::json identity(const Job& job, const Wad& wad, const DoomMap& map) {
  nlohmann::json id = doom_identity(job);
  id["n_polygons"] = linedef_sides(map);
  id["linedefs"] = map.linedefs.size();
  id["map_hash"] = map_hash(wad, map);
  if (job.doom->builder == DoomBuilder::Kind::External) id["builder_version"] = find_builder(job.heuristic).version;
  return id;
}

}  // namespace

nlohmann::json run_doom_job(const Job& job, const std::optional<PlantedSlowdown>& plant) {
  const auto start = std::chrono::steady_clock::now();
  const std::string path = doom_iwad_path(job.doom->iwad);
  const Wad& wad = doom_wad(job.doom->iwad);
  const DoomMap map = read_map(wad, job.doom->map, path);
  const DoomBuilder builder = doom_builder(job);
  DoomRunSettings settings;
  settings.seed = job.seed;
  settings.views = static_cast<int>(job.validation_views);
  const DoomRun run = run_doom(path, wad, map, builder, settings);
  nlohmann::json timings = nlohmann::json::object();
  nlohmann::json validation = nullptr;
  if (run.order) {
    validation = to_json(*run.order);
    split_timings(validation, timings, "validation_");
  }
  if (builder.kind == DoomBuilder::Kind::Heuristic) {
    const bool planted = plant && plant->heuristic == job.heuristic;
    time_ours(map, builder, job.seed, planted ? plant->factor : 1.0, timings);
  } else if (builder.kind == DoomBuilder::Kind::External && run.error.empty()) {
    time_external(path, wad, map, builder, run, timings);
  }
  nlohmann::json record{{"key", job.key},
                        {"id", identity(job, wad, map)},
                        {"metrics", metrics_json(run)},
                        {"invariants", invariants_json(run.check)},
                        {"validation", std::move(validation)},
                        {"ray_shooting", nullptr}};
  if (!run.error.empty()) record["error"] = run.error;
  timings["job_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record["timings"] = std::move(timings);
  return record;
}

}  // namespace bsp::sweep
