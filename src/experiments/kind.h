#pragma once
// An experiment kind as the suite and the sweep see it: how its blocks are read from a suite file,
// and what its records hold. Each kind defines one Kind in its own folder (src/experiments/KIND/);
// suite/kinds.cpp lists them, once. Nothing else in the sweep, the suite parser, the gate or the
// results knows one kind from another.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "experiments/block_reader.h"
#include "experiments/job.h"
#include "experiments/timing.h"

namespace bsp::experiments {

// One block of a suite file, parsed and validated.
class Block {
 public:
  virtual ~Block() = default;
  // Every job the block asks for, in any order: the suite sorts them and drops repeats. Throws
  // InputError or UsageError when what the block names cannot be found (an IWAD, a mesh).
  virtual Jobs expand() const = 0;
};

struct Kind {
  std::string_view name = {};       // as records' id.kind and Job::kind() say it
  std::string_view suite_key = {};  // the key of its blocks in a suite file ("blocks", "merges", ...)
  // Reads one block at `path` of the suite file; throws InputError ("FILE: PATH: problem").
  // nullptr: the block names only data this machine lacks (meshes not fetched), which the parser
  // said on stderr; the suite runs without it.
  std::unique_ptr<const Block> (*parse)(const BlockReader& reader, const nlohmann::json& block, const std::string& path) = nullptr;
  // Whether the parser expands each block to refuse one that runs nothing. Not where expanding
  // reads external data (Doom's IWADs), which fails with its own message when the suite expands.
  bool expand_when_parsed = true;
  // Its records' timing fields (timing.h), declared here and nowhere else.
  std::span<const TimingField> timings = {};
  // Identity fields that group its runs in aggregation beyond kind, scene, heuristic, shape and
  // the scene's parameters other than n and seed.
  std::span<const std::string_view> group_by = {};
  // The metrics and timings whose growth with the polygon count aggregation fits.
  std::span<const std::string_view> growth_metrics = {};
  std::span<const std::string_view> growth_timings = {};
  // The metrics and timings also fitted through one point per size (the sizes' geometric means over
  // seeds), with a 95% interval of the exponent: what the report's theory check compares with the
  // bounds.
  std::span<const std::string_view> size_growth_metrics = {};
  std::span<const std::string_view> size_growth_timings = {};
  // A timing also fitted against the fragments made (the cost per unit of output, which the
  // scene's density does not change); empty for none.
  std::string_view growth_against_fragments = {};
  // How the gate names a run's timing group beside its scene and heuristic: by the identity field
  // that stands for the shape, or by a fixed word when one is given (all runs of a scene and
  // heuristic then pool); and which identity field tells the runs of a group apart in messages
  // (printed "n=N" for n, bare otherwise).
  std::string_view timing_group_field = "shape";
  std::string_view timing_group_word = {};
  std::string_view instance_field = "n";
  // Whether a record's identity has the kind's own fields of the right types, beyond the ones
  // every identity has; nullptr: it has none. A report failing this is refused when read.
  bool (*identity_ok)(const nlohmann::json& id) = nullptr;
  // The heading of its record's section in analysis/SCHEMA.md ("RUN", "MERGE RUN", ...), which
  // must name every timing field above.
  std::string_view schema_section = {};
  // Whether a run's violations are ours to answer for, from its identity; nullptr: always. A Doom
  // run of nodes made by others reports their violations as facts about them, never failed.
  bool (*judged_for_violations)(const nlohmann::json& id) = nullptr;
};

}  // namespace bsp::experiments
