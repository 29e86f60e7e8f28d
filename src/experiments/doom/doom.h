#pragma once
// Doom runs: our leafy trees beside the external node builders and the nodes the WAD shipped with,
// on the same maps, measured and proved alike (map_nodes.h). A suite block of this kind is a "doom"
// entry: one job per IWAD, map, heuristic and seed; one per IWAD, map and external builder, and one
// for the shipped nodes, whatever the seeds (they consult none). The record is analysis/SCHEMA.md's
// DOOM RUN:
//  - metrics: the nodes' sizes and depths, whoever built them; for ours also the segments built
//    from, the build's fallbacks and mixed leaves, the map errors left out, and what rounding split
//    vertices to integers did;
//  - invariants: the structural check (validate/doom_check.h); validation: our trees' Embree order
//    check, null for the others; `error` (top level) when an external builder failed or its output
//    could not be read;
//  - timings. Ours: timed batches of the build and its conversion to vanilla lumps
//    (build_our_nodes), gated as builds are, planted slowdown included. An external builder: its
//    process's CPU time in kBatches runs, reported and not gated, since it is not our code and the
//    gate would judge the machine's process start-up more than the builder. The shipped nodes: none.
//
// Expanding a block reads its IWADs' directories (iwads.h): "every map" is what the IWAD holds,
// and a map a block names that the IWAD lacks is refused. A suite with a Doom block therefore does
// not expand without its IWADs: it fails at once with an InputError naming the file and the package
// to install, before any job runs, rather than after hours with every Doom job failed.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/doom/map_nodes.h"
#include "experiments/kind.h"

namespace bsp::experiments {

struct DoomBlock final : Block {
  std::vector<std::string> iwads;  // file names in the Doom data directory
  std::vector<std::string> maps;   // empty: every map of each IWAD
  // Labels: registered names, NAME:k=v,k=v variants, or Doom preset names (doom_presets()); empty:
  // every registered heuristic and every preset.
  std::vector<std::string> heuristics;
  std::vector<std::string> builders;  // external node builders (node_builders.h): zdbsp, glbsp
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = 4;  // eyes of the Embree order check of our trees

  Jobs expand() const override;
};

struct DoomSpec {
  std::string iwad;  // file name in the Doom data directory
  std::string map;
  // The builder's label: a heuristic label or Doom preset (kind Heuristic), the external builder's
  // name, or "shipped".
  std::string label;
  DoomBuilder builder;  // resolved from the label
  std::uint64_t seed = 0;   // ours only; 0 for the others
  std::uint32_t views = 0;  // ours only
};

class DoomJob final : public Job {
 public:
  explicit DoomJob(DoomSpec spec);
  std::string_view kind() const override { return "doom"; }
  // {kind: "doom", scene: the IWAD (what aggregation and the gate group by), scene_params: {}, iwad,
  // map, builder and heuristic (both the label), builder_kind ("heuristic" | "external" |
  // "shipped"), preset (or null), heuristic_params (resolved; {} for the others), shape: "leafy",
  // seed and views (null for the others), n: 0, command: the `bspbench doom ... --json` that
  // repeats the run}.
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const DoomSpec& spec() const { return spec_; }

 private:
  DoomSpec spec_;
};

// Who builds for a label of kind `kind`: a Doom preset's name or a heuristic label for ours.
DoomBuilder doom_builder(DoomBuilder::Kind kind, const std::string& label);

const Kind& doom_kind();

}  // namespace bsp::experiments
