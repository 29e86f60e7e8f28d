#include "experiments/doom/doom.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/hash.h"
#include "io/doom_iwads.h"
#include "experiments/doom/node_builders.h"
#include "experiments/heuristic_choice.h"
#include "experiments/reference_build.h"
#include "io/doom_map.h"
#include "io/doom_nodes.h"
#include "metrics/statistics.h"
#include "split/registry.h"

namespace bsp::experiments {

namespace {

using nlohmann::json;

constexpr const char* kBuilderKinds[] = {"heuristic", "external", "shipped"};
std::string_view kind_name(DoomBuilder::Kind kind) { return kBuilderKinds[static_cast<int>(kind)]; }

constexpr TimingField kTimings[] = {
    {"doom_cpu_samples", TimingRole::GatedSamples,
     "thread CPU seconds per build of a Doom map's nodes (leafy tree and vanilla lumps), one per timed batch of at "
     "least 2 ms (our heuristics only)"},
    {"doom_reference_samples", TimingRole::ReferenceSamples,
     "thread CPU seconds per Embree BVH build of the map's segments stood up as walls, one batch before each timed batch: the gate divides each sample by it (experiments/reference_build.h)"},
    {"doom_cpu_seconds", TimingRole::SamplesMedian, "the median of doom_cpu_samples"},
    {"doom_cpu_runs", TimingRole::SampleCount, "builds timed for the samples: depends on the machine's speed"},
    {"builder_cpu_samples", TimingRole::UngatedSamples,
     "an external node builder's CPU seconds (user + system of its process) in each of 5 runs; not gated"},
    {"builder_cpu_seconds", TimingRole::Cpu, "the median of builder_cpu_samples"},
    {"validation_seconds", TimingRole::Wall, "wall time of the Embree order check"},
    {"validation_rays_per_second", TimingRole::Rate, "rays cast per wall-clock second in the order check"},
    {"job_seconds", TimingRole::Wall, "wall time of the whole job"},
};

// What aggregation groups by and fits growth of (experiments/kind.h).
constexpr std::string_view kGroupBy[] = {"builder_kind"};
constexpr std::string_view kGrowthMetrics[] = {"segs", "splits", "nodes"};
constexpr std::string_view kGrowthTimings[] = {"doom_cpu_seconds", "builder_cpu_seconds"};

// Record fields from to_json(DoomRun) (map_nodes.h).
constexpr JsonField kMetricFields[] = {{"segs", "/segs"},           {"subsectors", "/subsectors"},
                                      {"nodes", "/nodes"},         {"splits", "/splits"},
                                      {"max_depth", "/max_depth"}, {"mean_depth", "/mean_depth"}};
// Ours only: what the build started from, what it did, and what rounding split vertices did.
constexpr JsonField kOurMetricFields[] = {{"segments", "/segments"},
                                         {"fallbacks", "/fallbacks"},
                                         {"mixed_leaves", "/mixed_leaves"},
                                         {"zero_length_linedefs", "/zero_length_linedefs"},
                                         {"coincident_sides", "/coincident_sides"},
                                         {"rounding_split_vertices", "/rounding/split_vertices"},
                                         {"rounding_max_shift", "/rounding/max_shift"},
                                         {"rounding_mean_shift", "/rounding/mean_shift"},
                                         {"rounding_collapsed_segs", "/rounding/collapsed_segs"}};
constexpr JsonField kInvariantFields[] = {{"violations", "/check_violations"},
                                         {"first_problems", "/check_problems"},
                                         {"worst_side_distance", "/worst_side_distance"},
                                         {"worst_convexity_distance", "/worst_convexity_distance"}};

// Every registered heuristic and every Doom preset: a block without heuristics sweeps them all, so a
// heuristic added to the registry is swept without further wiring.
std::vector<std::string> heuristic_labels(const DoomBlock& block) {
  if (!block.heuristics.empty()) return block.heuristics;
  std::vector<std::string> all;
  for (const auto& h : heuristics()) all.push_back(h.name);
  for (const auto& p : doom_presets()) all.push_back(p.name);
  return all;
}

std::vector<std::string> block_maps(const DoomBlock& block, const std::string& iwad) {
  const std::vector<std::string> all = map_names(doom_wad(iwad));
  if (block.maps.empty()) return all;
  for (const auto& m : block.maps)
    if (std::find(all.begin(), all.end(), m) == all.end()) throw InputError(doom_iwad_path(iwad) + ": no map " + m);
  return block.maps;
}

JobPtr doom_job(const std::string& iwad, const std::string& map, DoomBuilder::Kind kind, const std::string& label,
                std::uint64_t seed, std::uint32_t views) {
  return std::make_shared<DoomJob>(DoomSpec{iwad, map, label, doom_builder(kind, label), seed, views});
}

ParamSet resolved_params(const DoomBuilder& b) {
  if (b.kind != DoomBuilder::Kind::Heuristic) return {};
  return HeuristicChoice::of(b.name, b.params).resolved;
}

// The label as `bspbench doom --heuristics` takes it: a preset's name, or NAME:k=v:k=v.
std::string cli_heuristic(const DoomBuilder& b) {
  if (!b.preset.empty()) return b.preset;
  std::string out = b.name;
  for (const auto& [k, v] : b.params) out += ":" + k + "=" + v;
  return out;
}

std::string command(const DoomSpec& s) {
  const std::string head = "bspbench doom --iwad " + s.iwad + " --maps " + s.map;
  switch (s.builder.kind) {
    case DoomBuilder::Kind::Heuristic:
      return head + plugin_arguments(s.builder.name) + " --heuristics " + cli_heuristic(s.builder) + " --seed " + std::to_string(s.seed) + " --views " +
             std::to_string(s.views) + " --json";
    case DoomBuilder::Kind::External: return head + " --heuristics '' --builders " + s.builder.name + " --json";
    case DoomBuilder::Kind::Shipped: break;
  }
  return head + " --heuristics '' --json";  // the shipped nodes are in every `bspbench doom` run
}

// The key: "doom", IWAD, map, builder kind and label; for our heuristics also their resolved
// parameters, the seed and the views.
std::string doom_key(const DoomSpec& s) {
  Hasher h;
  h.add_string("doom");
  h.add_string(s.iwad);
  h.add_string(s.map);
  h.add_string(kind_name(s.builder.kind));
  h.add_string(s.label);
  if (s.builder.kind == DoomBuilder::Kind::Heuristic) {
    h.add_string(s.builder.name);
    h.add_string(resolved_params(s.builder).canonical());
    add_plugin_identity(h, s.builder.name);
    h.add_u64(s.seed);
    h.add_u64(s.views);
  }
  return h.hex();
}

// The map's lumps as the IWAD holds them: says which map was read, whatever the IWAD's release.
std::string map_hash(const Wad& wad, const DoomMap& map) {
  Hasher h;
  h.add_string(wad_bytes(single_map_pwad(wad, map)));
  return h.hex();
}

// The segments are made once, outside the timed region, as run_doom times ours.
void time_ours(const DoomMap& map, const DoomBuilder& b, std::uint64_t seed, double plant, json& timings) {
  const DoomSegs segs = doom_segs(map);
  const ReferenceBuild reference(segs.segs);
  const TimedBatches batches =
      time_batches([&] { build_our_nodes(map, segs, b, seed); }, plant, [&] { reference.run(); });
  timings["doom_cpu_samples"] = batches.samples;
  timings["doom_reference_samples"] = batches.reference;
  timings["doom_cpu_runs"] = batches.runs;
  timings["doom_cpu_seconds"] = batches.median();
}

// The first run's CPU time and kBatches - 1 more runs: one process start each, so no batches.
void time_external(const std::string& path, const Wad& wad, const DoomMap& map, const DoomBuilder& b,
                   const DoomRun& first, json& timings) {
  std::vector<double> samples{first.cpu_seconds};
  while (samples.size() < static_cast<std::size_t>(kBatches)) samples.push_back(run_doom(path, wad, map, b, {}).cpu_seconds);
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

// ---- the block's parser ----

// A Doom block's heuristic: a Doom preset's name or a heuristic label.
std::vector<std::string> doom_heuristics(const BlockReader& r, const json& j, const std::string& path) {
  std::vector<std::string> out;
  std::map<std::string, std::string> seen;
  r.each(j, path, "leave \"heuristics\" out for every heuristic and Doom preset", [&](const json& h, const std::string& p) {
    std::string identity;
    if (h.is_string() && doom_preset(h.get<std::string>())) {
      out.push_back(h.get<std::string>());
      identity = "preset " + out.back();
    } else {
      out.push_back(r.heuristic(h, p, identity));
    }
    r.once(seen, identity, p);
  });
  return out;
}

std::unique_ptr<const Block> parse_block(const BlockReader& r, const json& j, const std::string& path) {
  r.expect(j, j.is_object(), path, "an object");
  r.check_keys(j, path, {"iwads", "maps", "heuristics", "builders", "seeds", "views"});
  auto b = std::make_unique<DoomBlock>();
  b->iwads = r.names(r.required(j, path, "iwads"), child(path, "iwads"), "name at least one IWAD", [](const std::string& name) {
    if (name.empty() || name.find('/') != std::string::npos)
      throw UsageError("'" + name + "' is not a file name in the Doom data directory");
  });
  if (const json* m = r.optional(j, "maps"))
    b->maps = r.names(*m, child(path, "maps"), "leave \"maps\" out for every map", [](const std::string&) {});
  if (const json* h = r.optional(j, "heuristics")) b->heuristics = doom_heuristics(r, *h, child(path, "heuristics"));
  if (const json* bs = r.optional(j, "builders"))
    b->builders = r.names(*bs, child(path, "builders"), "leave \"builders\" out for none", check_builder_name);
  b->seeds = r.seeds(j, path);
  if (const json* v = r.optional(j, "views")) b->views = static_cast<std::uint32_t>(r.integer(*v, child(path, "views"), 0, kMaxViews));
  return b;
}

}  // namespace

DoomBuilder doom_builder(DoomBuilder::Kind kind, const std::string& label) {
  switch (kind) {
    case DoomBuilder::Kind::Heuristic: {
      if (auto preset = doom_preset(label)) return *preset;
      const HeuristicLabel v = split_heuristic_label(label);
      params_of(v.name);  // rejects an unknown name
      return {DoomBuilder::Kind::Heuristic, v.name, v.params, {}};
    }
    case DoomBuilder::Kind::External: return {DoomBuilder::Kind::External, label, {}, {}};
    case DoomBuilder::Kind::Shipped: break;
  }
  return {DoomBuilder::Kind::Shipped, "shipped", {}, {}};
}

Jobs DoomBlock::expand() const {
  for (const auto& b : builders) check_builder_name(b);
  Jobs out;
  for (const auto& iwad : iwads)
    for (const auto& map : block_maps(*this, iwad)) {
      for (const auto& label : heuristic_labels(*this))
        for (auto seed : seeds) out.push_back(doom_job(iwad, map, DoomBuilder::Kind::Heuristic, label, seed, views));
      for (const auto& b : builders) out.push_back(doom_job(iwad, map, DoomBuilder::Kind::External, b, 0, 0));
      out.push_back(doom_job(iwad, map, DoomBuilder::Kind::Shipped, "shipped", 0, 0));
    }
  return out;
}

DoomJob::DoomJob(DoomSpec spec) : spec_(std::move(spec)) { set_identity(doom_key(spec_), 0); }

nlohmann::json DoomJob::identity() const {
  const DoomBuilder& b = spec_.builder;
  const bool ours = b.kind == DoomBuilder::Kind::Heuristic;
  return {{"kind", "doom"},
          {"scene", spec_.iwad},
          {"scene_params", json::object()},
          {"iwad", spec_.iwad},
          {"map", spec_.map},
          {"builder", spec_.label},
          {"builder_kind", kind_name(b.kind)},
          {"preset", b.preset.empty() ? json() : json(b.preset)},
          {"heuristic", spec_.label},
          {"heuristic_params", ours ? resolved_params(b).to_json() : json::object()},
          {"shape", shape_name(Shape::Leafy)},
          {"seed", ours ? json(spec_.seed) : json()},
          {"views", ours ? json(spec_.views) : json()},
          {"n", 0},
          {"command", command(spec_)}};
}

nlohmann::json DoomJob::run(const RunContext& context) const {
  const double start = wall_seconds();
  const std::string path = doom_iwad_path(spec_.iwad);
  const Wad& wad = doom_wad(spec_.iwad);
  const DoomMap map = read_map(wad, spec_.map, path);
  DoomRunSettings settings;
  settings.seed = spec_.seed;
  settings.views = static_cast<int>(spec_.views);
  const DoomRun run = run_doom(path, wad, map, spec_.builder, settings);
  const json described = to_json(run);
  json timings = json::object();
  json validation = nullptr;
  if (described.contains("order")) {
    validation = described["order"];
    split_timings(validation, timings, "validation_", kTimings);
  }
  const bool ours = spec_.builder.kind == DoomBuilder::Kind::Heuristic;
  if (ours) time_ours(map, spec_.builder, spec_.seed, context.slowdown(spec_.label), timings);
  else if (spec_.builder.kind == DoomBuilder::Kind::External && run.error.empty())
    time_external(path, wad, map, spec_.builder, run, timings);
  json id = identity();
  id["n_polygons"] = linedef_sides(map);
  id["linedefs"] = map.linedefs.size();
  id["map_hash"] = map_hash(wad, map);
  if (spec_.builder.kind == DoomBuilder::Kind::External) id["builder_version"] = find_builder(spec_.label).version;
  json metrics = json::object(), invariants = json::object();
  pick_fields(described, kMetricFields, metrics);
  if (ours) pick_fields(described, kOurMetricFields, metrics);
  pick_fields(described, kInvariantFields, invariants);
  json record = make_record(*this, std::move(id), std::move(metrics), std::move(invariants),
                            std::move(validation), nullptr, std::move(timings), start);
  if (!run.error.empty()) record["error"] = run.error;
  return record;
}

namespace {

// What reports must hold of a Doom run's identity: its map and who built its nodes.
bool map_and_builder(const json& id) {
  return id.contains("map") && id["map"].is_string() && id.contains("builder_kind") && id["builder_kind"].is_string();
}

// Only our trees' violations are ours; an external builder's or the WAD's are facts about them.
bool ours(const json& id) { return id.value("builder_kind", "") == "heuristic"; }

}  // namespace

const Kind& doom_kind() {
  static const Kind kind{
      .name = "doom",
      .suite_key = "doom",
      .parse = parse_block,
      .expand_when_parsed = false,
      .timings = kTimings,
      .group_by = kGroupBy,
      .growth_metrics = kGrowthMetrics,
      .growth_timings = kGrowthTimings,
      .timing_group_word = "doom",
      .instance_field = "map",
      .identity_ok = map_and_builder,
      .schema_section = "DOOM RUN",
      .judged_for_violations = ours,
  };
  return kind;
}

}  // namespace bsp::experiments
