// bspbench doom: our heuristics and the installed node builders on the maps of a Doom WAD, side by
// side (experiments/doom/map_nodes.h): splits, segs, subsectors, nodes, depth and CPU time per map and in
// total, every output proved structurally and ours also against Embree; progress with the time left
// on stderr. Exit code 1 when any of our outputs fails a check.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/errors.h"
#include "common/progress.h"
#include "io/wad.h"
#include "experiments/heuristic_choice.h"
#include "split/registry.h"
#include "io/doom_iwads.h"
#include "experiments/doom/map_nodes.h"
#include "experiments/doom/node_builders.h"

namespace bsp::cli {

namespace {

using experiments::DoomBuilder;
using experiments::DoomRun;
using experiments::DoomRunSettings;
using experiments::DoomTotals;

std::vector<std::string> split_list(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

// A Doom preset, or NAME or NAME:k=v:k=v, each name a registered heuristic and each parameter one
// it has.
DoomBuilder heuristic_builder(const std::string& spec) {
  if (const auto preset = experiments::doom_preset(spec)) return *preset;
  const auto parts = split_list(spec, ':');
  if (parts.empty()) throw UsageError("--heuristics has an empty entry");
  DoomBuilder b{DoomBuilder::Kind::Heuristic, parts[0], {}, {}};
  for (std::size_t i = 1; i < parts.size(); ++i) b.params.push_back(parse_assignment(parts[i]));
  experiments::HeuristicChoice::of(b.name, b.params);  // rejects unknown names, parameters and values now
  return b;
}

std::vector<DoomBuilder> builders_from(const std::string& heuristics_text, const std::string& builders_text) {
  std::vector<DoomBuilder> out;
  if (heuristics_text == "all") {
    for (const auto& h : heuristics()) out.push_back({DoomBuilder::Kind::Heuristic, h.name, {}, {}});
    for (const auto& p : experiments::doom_presets()) out.push_back(*experiments::doom_preset(p.name));
  } else {
    for (const auto& spec : split_list(heuristics_text, ',')) out.push_back(heuristic_builder(spec));
  }
  for (const auto& name : split_list(builders_text, ',')) {
    if (experiments::find_builder(name).path.empty()) throw UsageError("node builder " + name + " is not installed");
    out.push_back({DoomBuilder::Kind::External, name, {}, {}});
  }
  out.push_back({DoomBuilder::Kind::Shipped, "shipped", {}, {}});
  return out;
}

std::vector<std::string> maps_from(const Wad& wad, const std::string& text, const std::string& file) {
  const std::vector<std::string> all = map_names(wad);
  if (text == "all") return all;
  std::vector<std::string> out = split_list(text, ',');
  for (const auto& m : out)
    if (std::find(all.begin(), all.end(), m) == all.end()) throw InputError(file + ": no map " + m);
  return out;
}

// A WAD named without a directory that is not in the working directory is looked up where Debian
// installs them (or in BSPBENCH_DOOM_DIR), as Doom ports search DOOMWADDIR: --iwad freedoom2.wad.
std::string resolve_wad(const std::string& name) {
  if (name.find('/') != std::string::npos || std::filesystem::exists(name)) return name;
  const auto installed = std::filesystem::path(doom_data_dir()) / name;
  return std::filesystem::exists(installed) ? installed.string() : name;
}

void print_totals(const std::vector<DoomTotals>& totals) {
  std::printf("%-28s %5s %9s %9s %9s %11s %9s %9s %9s %6s\n", "builder", "maps", "CPU s", "splits", "segs",
              "subsectors", "nodes", "max depth", "leaf depth", "failed");
  for (const DoomTotals& t : totals)
    std::printf("%-28s %5zu %9.3f %9lld %9zu %11zu %9zu %9.1f %9.2f %6zu\n", t.builder.c_str(), t.maps, t.cpu_seconds,
                static_cast<long long>(t.splits), t.segs, t.subsectors, t.nodes, t.mean_max_depth, t.mean_leaf_depth,
                t.failed);
}

int run(Args& args) {
  const std::string iwad = resolve_wad(args.required("--iwad"));
  const std::string maps_text = args.option("--maps").value_or("all");
  const std::string heuristics_text = args.required("--heuristics");
  const std::string builders_text = args.option("--builders").value_or("");
  DoomRunSettings settings;
  settings.out_dir = args.option("--out").value_or("");
  settings.seed = static_cast<std::uint64_t>(args.integer("--seed", 0, (1LL << 62)).value_or(1));
  settings.views = static_cast<int>(args.integer("--views", 1, 100).value_or(settings.views));
  const bool json = args.flag("--json");
  args.finish();
  const std::vector<DoomBuilder> builders = builders_from(heuristics_text, builders_text);
  const Wad wad = read_wad(iwad);
  const std::vector<std::string> maps = maps_from(wad, maps_text, iwad);
  // Every map is read (and refused if malformed) before anything is built or written.
  std::vector<DoomMap> read;
  for (const auto& name : maps) read.push_back(read_map(wad, name, iwad));
  // Progress on stderr: a map's runs weigh as its linedefs, which is what building it costs.
  double weight = 0;
  for (const DoomMap& map : read) weight += static_cast<double>(map.linedefs.size() * builders.size());
  Progress progress(std::cerr, ::isatty(STDERR_FILENO) != 0, "doom", "runs", read.size() * builders.size(), weight);
  std::vector<DoomRun> runs;
  for (const DoomMap& map : read)
    for (const DoomBuilder& b : builders) {
      runs.push_back(experiments::run_doom(iwad, wad, map, b, settings));
      progress.job_done(static_cast<double>(map.linedefs.size()));
    }
  progress.finish();
  const std::vector<DoomTotals> totals = experiments::doom_totals(runs);
  bool ours_ok = true;
  for (const DoomRun& r : runs) ours_ok &= r.kind != DoomBuilder::Kind::Heuristic || r.ok;
  if (json) {
    nlohmann::json out = {{"iwad", iwad}, {"maps", maps}, {"seed", settings.seed}, {"builders", nlohmann::json::object()},
                          {"runs", nlohmann::json::array()}, {"totals", nlohmann::json::array()}};
    for (const DoomBuilder& b : builders)
      if (b.kind == DoomBuilder::Kind::External) out["builders"][b.name] = experiments::find_builder(b.name).version;
    for (const DoomRun& r : runs) out["runs"].push_back(experiments::to_json(r));
    for (const DoomTotals& t : totals) out["totals"].push_back(experiments::to_json(t));
    std::cout << out.dump() << "\n";
  } else {
    print_totals(totals);
  }
  return ours_ok ? 0 : 1;
}

}  // namespace

Command doom_command() {
  return {"doom",
          "--iwad FILE [--maps all|MAP,...] --heuristics all|NAME[:k=v...][,...] [--builders zdbsp,glbsp] [--out DIR] "
          "[--seed S] [--views K] [--json]",
          "build the maps of a Doom WAD with our heuristics and with installed node builders, and compare",
          run,
          {{"--iwad FILE",
            "the WAD whose maps are built (an IWAD or a PWAD); a bare name not in the working directory is looked "
            "up in BSPBENCH_DOOM_DIR, default /usr/share/games/doom"},
           {"--maps all|MAP,...", "the maps to build (default all)"},
           {"--heuristics all|NAME[:k=v...][,...]",
            "our heuristics or searches (bspbench catalog), each with optional parameters, or the presets doom-splits "
            "(min-relation, 64 candidates, min_relation 0.05), doom-depth (min_relation 0.3) and doom-search (the best "
            "of four zennode builds, x4 from 200 to 3000); all: every heuristic and the presets"},
           {"--builders zdbsp,glbsp", "external node builders to run on the same maps, each map in its own PWAD"},
           {"--out DIR", "write each map rebuilt by each heuristic as DIR/HEURISTIC/MAP.wad"},
           {"--seed S", "seed of the heuristics' randomness (default 1)"},
           {"--views K", "eyes (the map's first things) of the Embree order check of our trees (default 4)"},
           {"--json", "print one JSON object (every run and the totals) instead of the totals table"}}};
}

}  // namespace bsp::cli
