#pragma once
// One Doom map built by one of our heuristics or by an external node builder, measured by one
// parser (io/doom_tree_stats.h) and proved by one checker (validate/doom_check.h), so research
// heuristics and production builders are compared on the same terms.
//
// Ours: the map's linedef sides become segments (io/doom_nodes.h), a leafy tree with one sector
// per leaf is built, and its vanilla lumps are written; the CPU time covers building and writing
// the lumps, on one thread, as the external builders run. Our back-to-front order is also proved
// against Embree from the map's things (validate_segment_tree). External builders run in their own
// process on the map alone in a PWAD (experiments/doom/node_builders.h), CPU time from rusage; what they
// write is read back and checked like ours. "shipped" is the nodes the WAD came with.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "io/doom_map.h"
#include "io/doom_nodes.h"
#include "io/doom_tree_stats.h"
#include "validate/doom_check.h"
#include "validate/order_check.h"

namespace bsp::experiments {

// Who made a map's nodes.
struct DoomBuilder {
  enum class Kind : std::uint8_t { Heuristic, External, Shipped };
  Kind kind = Kind::Heuristic;
  std::string name;          // heuristic name, external tool, or "shipped"
  ParamAssignments params;   // heuristics only
  std::string preset;        // the DoomPreset it came from, if any
  std::string label() const;  // the preset, or name with "k=v,..." in braces when params are set
};

// Heuristic settings tuned on the 68 Freedoom maps against the node builders (docs/doom.md):
// min-relation over 64 sampled candidates, its balance threshold set low for few splits or higher
// for shallow trees.
struct DoomPreset {
  std::string name, heuristic;
  ParamAssignments params;
  std::string aim;  // one line: what it was tuned for
};
const std::vector<DoomPreset>& doom_presets();
// A preset by name, as a builder; nullopt for another name.
std::optional<DoomBuilder> doom_preset(const std::string& name);

struct DoomRunSettings {
  std::uint64_t seed = 1;
  int views = 4;                 // eyes of the Embree order check: the first things of the map
  double builder_timeout = 120;  // seconds of wall time per external builder run
  std::string out_dir;           // when set, ours are written as DIR/LABEL/MAP.wad
};

struct DoomRun {
  std::string map, builder;
  DoomBuilder::Kind kind = DoomBuilder::Kind::Heuristic;
  bool ok = true;        // built, read and proved
  std::string error;     // why not, when a builder failed or its output could not be read
  DoomTreeStats stats;
  double cpu_seconds = 0;
  DoomCheckReport check;
  // Ours only.
  std::uint64_t segments = 0, fallbacks = 0, mixed_leaves = 0;
  std::uint64_t dropped = 0, coincident = 0;  // zero-length linedefs, coincident sides (DoomSegs)
  RoundingStats rounding;
  std::optional<ValidationReport> order;
};

// The eyes of the order check: the positions of the map's first `views` things, moved off the
// integer grid by a fraction of a unit so that no wall is seen edge-on.
std::vector<Vec3> doom_eyes(const DoomMap& map, int views);

// Our leafy tree of the map's segments (doom_segs(map)) by `builder` (a heuristic) and its vanilla
// lumps, on one thread: the work whose CPU time run_doom reports for our heuristics, apart so a
// sweep can time it in batches (doom.h) without the checks.
struct OurNodes {
  Tree tree;
  VanillaBuild vanilla;
};
OurNodes build_our_nodes(const DoomMap& map, const DoomSegs& segs, const DoomBuilder& builder, std::uint64_t seed);

DoomRun run_doom(const std::string& wad_path, const Wad& wad, const DoomMap& map, const DoomBuilder& builder,
                 const DoomRunSettings& settings);

nlohmann::json to_json(const DoomRun& run);

// One builder's runs summed over maps, as the node-builder comparisons report them.
struct DoomTotals {
  std::string builder;
  std::size_t maps = 0, failed = 0;  // failed: not built, not readable, or a check violated
  double cpu_seconds = 0;
  std::int64_t splits = 0;
  std::size_t segs = 0, subsectors = 0, nodes = 0;
  double mean_max_depth = 0;   // over maps
  double mean_leaf_depth = 0;  // over maps, of each map's mean subsector depth
};

// Totals per builder, in the order builders first appear in `runs`.
std::vector<DoomTotals> doom_totals(const std::vector<DoomRun>& runs);
nlohmann::json to_json(const DoomTotals& t);

}  // namespace bsp::experiments
