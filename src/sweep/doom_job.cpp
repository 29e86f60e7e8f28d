#include "sweep/doom_job.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/hash.h"
#include "io/doom_map.h"
#include "split/registry.h"
#include "sweep/node_builders.h"

namespace bsp::sweep {

namespace {

constexpr const char* kBuilderKinds[] = {"heuristic", "external", "shipped"};

std::string_view kind_name(DoomBuilder::Kind kind) { return kBuilderKinds[static_cast<int>(kind)]; }

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

Job doom_job(const std::string& iwad, const std::string& map, DoomBuilder::Kind kind, const std::string& label,
             std::uint64_t seed, std::uint32_t views) {
  Job job;
  job.scene = iwad;
  job.heuristic = label;
  job.shape = Shape::Leafy;
  job.seed = seed;
  job.validation_views = views;
  job.doom = DoomParams{iwad, map, kind};
  assign_key(job);
  return job;
}

ParamSet resolved_params(const DoomBuilder& b) {
  if (b.kind != DoomBuilder::Kind::Heuristic) return {};
  const HeuristicInfo& h = find_heuristic(b.name);
  return ParamSet::resolve(h.params, b.params, "heuristic " + h.name);
}

// The label as `bspbench doom --heuristics` takes it: a preset's name, or NAME:k=v:k=v.
std::string cli_heuristic(const DoomBuilder& b) {
  if (!b.preset.empty()) return b.preset;
  std::string out = b.name;
  for (const auto& [k, v] : b.params) out += ":" + k + "=" + v;
  return out;
}

std::string doom_command(const Job& job, const DoomBuilder& b) {
  const DoomParams& d = *job.doom;
  std::string command = "bspbench doom --iwad " + d.iwad + " --maps " + d.map;
  switch (b.kind) {
    case DoomBuilder::Kind::Heuristic:
      return command + " --heuristics " + cli_heuristic(b) + " --seed " + std::to_string(job.seed) + " --views " +
             std::to_string(job.validation_views) + " --json";
    case DoomBuilder::Kind::External: return command + " --heuristics '' --builders " + b.name + " --json";
    case DoomBuilder::Kind::Shipped: break;
  }
  return command + " --heuristics '' --json";  // the shipped nodes are in every `bspbench doom` run
}

}  // namespace

std::string doom_data_dir() {
  const char* dir = std::getenv("BSPBENCH_DOOM_DIR");
  return dir && *dir ? dir : "/usr/share/games/doom";
}

std::string doom_iwad_path(const std::string& iwad) { return (std::filesystem::path(doom_data_dir()) / iwad).string(); }

const Wad& doom_wad(const std::string& iwad) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<const Wad>> read;
  const std::string path = doom_iwad_path(iwad);
  const std::lock_guard lock(mutex);
  auto& wad = read[path];
  if (!wad) {
    if (!std::filesystem::exists(path))
      throw InputError(path + ": no such IWAD (apt-get install freedoom, or set BSPBENCH_DOOM_DIR to its directory)");
    wad = std::make_unique<const Wad>(read_wad(path));
  }
  return *wad;
}

void expand_doom_block(const DoomBlock& block, std::vector<Job>& out) {
  for (const auto& b : block.builders) check_builder_name(b);
  for (const auto& iwad : block.iwads)
    for (const auto& map : block_maps(block, iwad)) {
      for (const auto& label : heuristic_labels(block))
        for (auto seed : block.seeds)
          out.push_back(doom_job(iwad, map, DoomBuilder::Kind::Heuristic, label, seed, block.views));
      for (const auto& b : block.builders) out.push_back(doom_job(iwad, map, DoomBuilder::Kind::External, b, 0, 0));
      out.push_back(doom_job(iwad, map, DoomBuilder::Kind::Shipped, "shipped", 0, 0));
    }
}

DoomBuilder doom_builder(const Job& job) {
  switch (job.doom->builder) {
    case DoomBuilder::Kind::Heuristic: {
      if (auto preset = doom_preset(job.heuristic)) return *preset;
      const HeuristicVariant v = parse_heuristic_variant(job.heuristic);
      return {DoomBuilder::Kind::Heuristic, find_heuristic(v.name).name, v.params, {}};
    }
    case DoomBuilder::Kind::External: return {DoomBuilder::Kind::External, job.heuristic, {}, {}};
    case DoomBuilder::Kind::Shipped: break;
  }
  return {DoomBuilder::Kind::Shipped, "shipped", {}, {}};
}

std::string doom_key(const Job& job) {
  const DoomBuilder b = doom_builder(job);
  Hasher h;
  h.add_string("doom");
  h.add_string(job.doom->iwad);
  h.add_string(job.doom->map);
  h.add_string(kind_name(b.kind));
  h.add_string(job.heuristic);
  if (b.kind == DoomBuilder::Kind::Heuristic) {
    h.add_string(b.name);
    h.add_string(resolved_params(b).canonical());
    h.add_u64(job.seed);
    h.add_u64(job.validation_views);
  }
  return h.hex();
}

nlohmann::json doom_identity(const Job& job) {
  const DoomBuilder b = doom_builder(job);
  const bool ours = b.kind == DoomBuilder::Kind::Heuristic;
  return {{"kind", "doom"},
          {"scene", job.doom->iwad},
          {"scene_params", nlohmann::json::object()},
          {"iwad", job.doom->iwad},
          {"map", job.doom->map},
          {"builder", job.heuristic},
          {"builder_kind", kind_name(b.kind)},
          {"preset", b.preset.empty() ? nlohmann::json() : nlohmann::json(b.preset)},
          {"heuristic", job.heuristic},
          {"heuristic_params", ours ? resolved_params(b).to_json() : nlohmann::json::object()},
          {"shape", shape_name(Shape::Leafy)},
          {"seed", ours ? nlohmann::json(job.seed) : nlohmann::json()},
          {"views", ours ? nlohmann::json(job.validation_views) : nlohmann::json()},
          {"n", 0},
          {"command", doom_command(job, b)}};
}

}  // namespace bsp::sweep
