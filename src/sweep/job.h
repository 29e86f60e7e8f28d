#pragma once
// One run of a sweep and its identity. A job's key is a hash of everything that determines its
// deterministic results (scene, resolved scene parameters, heuristic, resolved heuristic parameters,
// shape, seed, validation views), so journals, shards, merges and regression gates all match runs by
// key. The seed feeds both the scene generator and the heuristic, as in `bspbench build --seed`.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "sweep/suite.h"
#include "tree/tree.h"

namespace bsp::sweep {

struct Job {
  std::string scene;
  ParamAssignments scene_params;  // n and seed when the generator has them
  std::string heuristic;  // a HeuristicVariant's label; kIncrementalLabel (tree/build.h) for an incremental build
  bool incremental = false;  // Thibault–Naylor insertion in a seeded shuffled order; no heuristic
  Shape shape = Shape::Strict;
  std::uint64_t seed = 1;
  std::uint64_t n = 0;  // requested size; 0 when the generator has no `n`
  std::uint32_t validation_views = 0;
  std::string key;  // 16 hex digits, see the header comment
};

// A suite's heuristic entry: a registered name, "NAME", or a name with parameters,
// "NAME:k=v,k=v" (e.g. "weighted:candidates=0", the exhaustive variant). The whole text labels the
// runs in reports and in the gate's groups, so a variant is compared with itself only.
struct HeuristicVariant {
  std::string name;
  ParamAssignments params;
};
HeuristicVariant parse_heuristic_variant(const std::string& label);

// Every job of the suite, without duplicates, in a fixed order: largest sizes first (so a parallel
// run starts its long jobs early), ties broken by key.
std::vector<Job> expand(const Suite& suite);

struct Shard {
  std::uint32_t index = 0;  // 0-based
  std::uint32_t count = 1;
};
// Parses "i/N" with 0 <= i < N; throws UsageError otherwise.
Shard parse_shard(const std::string& text);
// The jobs shard `s` runs: every count-th job of the expanded order starting at index, which spreads
// sizes evenly over shards. Deterministic, and the shards partition the suite.
std::vector<Job> shard_jobs(const std::vector<Job>& jobs, Shard s);

// Hash of the suite's name and every job key: two reports come from the same suite definition
// exactly when these agree.
std::string definition_hash(const std::string& suite_name, const std::vector<Job>& jobs);

// {scene, scene_params, heuristic, heuristic_params, build, shape, seed, n, validation_views}: the identity
// printed in reports and regression tables, with the `bspbench build` command that rebuilds the tree.
nlohmann::json job_identity(const Job& job);

// Fills job.key from the other fields (resolving parameters, so defaults count).
void assign_key(Job& job);

}  // namespace bsp::sweep
