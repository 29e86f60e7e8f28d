#pragma once
// Doom jobs of a sweep (job.h): a DoomBlock's jobs, their keys, identities and builders, and the
// IWADs they read.
//
// IWADs are named by file name and looked up in the Doom data directory: $BSPBENCH_DOOM_DIR, else
// /usr/share/games/doom, where Debian's freedoom package installs freedoom1.wad and freedoom2.wad
// (as Doom ports search DOOMWADDIR). Names rather than paths keep keys, identities and commands the
// same on every machine; the map's content hash in each record (run_doom_job.h) says which maps
// were read.
//
// Expanding a block reads its IWADs' directories: "every map" is what the IWAD holds, and a map a
// block names that the IWAD lacks is refused. A suite with a Doom block therefore does not expand
// without its IWADs: it fails at once with an InputError naming the file and the package to
// install, before any job runs, rather than after hours with every Doom job failed.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "io/wad.h"
#include "sweep/doom_run.h"
#include "sweep/job.h"
#include "sweep/suite.h"

namespace bsp::sweep {

// $BSPBENCH_DOOM_DIR, or /usr/share/games/doom when it is unset or empty.
std::string doom_data_dir();
std::string doom_iwad_path(const std::string& iwad);

// The IWAD, read once per process and shared by every job that reads it; thread-safe. Throws
// InputError naming the path (and `apt-get install freedoom`) when it is missing or unreadable.
const Wad& doom_wad(const std::string& iwad);

// Per IWAD and map: one job per heuristic label and seed, one per external builder and one for the
// shipped nodes (neither consults a seed or eyes: their seed and views are 0). Throws UsageError
// for an unknown heuristic, parameter or builder, InputError for a missing IWAD or map.
void expand_doom_block(const DoomBlock& block, std::vector<Job>& out);

// The key (job.h): "doom", IWAD, map, builder kind and label; for our heuristics also their
// resolved parameters, the seed and the views.
std::string doom_key(const Job& job);

// Who builds the job's nodes, as run_doom takes it: a label is a Doom preset's name when one has
// it, else a heuristic label (NAME or NAME:k=v,k=v).
DoomBuilder doom_builder(const Job& job);

// {kind: "doom", scene: the IWAD (what aggregation and the gate group by), scene_params: {}, iwad,
// map, builder and heuristic (both the label: what reports name the builder by, and what
// aggregation and the gate group by), builder_kind ("heuristic" | "external" | "shipped"), preset
// (the Doom preset's name, or null), heuristic_params (resolved; {} for the others), shape:
// "leafy" (every seg in a convex leaf), seed and views (null for the others), n: 0, command: the
// `bspbench doom ... --json` that repeats the run}.
nlohmann::json doom_identity(const Job& job);

}  // namespace bsp::sweep
