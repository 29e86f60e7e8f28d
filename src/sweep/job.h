#pragma once
// One run of a sweep and its identity. A job's key is a hash of everything that determines its
// deterministic results (scene, resolved scene parameters, heuristic, resolved heuristic parameters,
// shape, seed, validation views; for a merge job the operation, both operands' resolved parameters
// and the points checked), so journals, shards, merges and regression gates all match runs by key.
// The seed feeds both the scene generator and the heuristic, as in `bspbench build --seed`.
//
// Five kinds of job: a drawing job builds one scene's tree and measures it (run_job.h); a merge job
// (`op` set) builds the two operands of a solid pair (solid_pairs.h) as solid trees and merges them
// by a set operation (run_merge_job.h); an animate job (`animate` set) keeps an animated scene's
// tree by an update strategy over its frames, and an occlude job (`occlude`) culls a scene's tree
// by beam tracing from the metric views (run_dynamic_jobs.h); a Doom job (`doom` set) builds one
// map's nodes with one of our heuristics or an external builder, or reads the shipped ones
// (doom_job.h, run_doom_job.h).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "scene/scene.h"
#include "solid/merge.h"
#include "solid_pairs.h"
#include "sweep/doom_run.h"
#include "sweep/suite.h"
#include "tree/tree.h"

namespace bsp::sweep {

// An animate job's animation (generators/animation.h) and update strategy (dynamic/updater.h).
struct AnimateParams {
  std::string strategy;
  std::uint32_t moving = 4;
  std::uint32_t frames = 100;
  std::string object = "sphere";
  std::uint64_t object_n = 80;
  double size = 0.04, speed = 0.004, spin = 0.02;
  std::uint32_t check_every = 1;  // frames checked: every N-th and the last
  std::uint32_t drift_every = 0;  // frames also built fresh: every N-th and the last; 0 none
};

// A Doom job's map and who builds its nodes; the job's `heuristic` is the builder's label (a
// heuristic label of the DoomBlock, the external builder's name, or "shipped").
struct DoomParams {
  std::string iwad;  // file name in the Doom data directory
  std::string map;
  DoomBuilder::Kind builder = DoomBuilder::Kind::Heuristic;
};

// A drawing job's mesh (a file:PATH or mesh:NAME scene): the file it reads, and the hash of the
// file's bytes, which takes the place of a generator's resolved parameters in the job's key beside
// the scene's label: a changed file is another run, and so is the same file under another label.
struct SceneFile {
  std::string path;
  std::string hash;  // 16 hex digits
};

enum class JobKind : std::uint8_t { Draw, Merge, Animate, Occlude, Doom };

struct Job {
  std::string scene;
  ParamAssignments scene_params;  // n and seed when the generator has them
  std::string heuristic;  // a HeuristicVariant's label; kIncrementalLabel (tree/build.h) for an incremental build
  bool incremental = false;  // Thibault–Naylor insertion in a seeded shuffled order; no heuristic
  Shape shape = Shape::Strict;
  std::uint64_t seed = 1;
  std::uint64_t n = 0;  // requested size; 0 when the generator has no `n`
  std::uint32_t validation_views = 0;
  std::optional<SetOp> op;  // merge jobs: `scene` names a solid pair, `n` is each operand's size
  std::uint64_t points = 0;  // merge jobs: points classified against CGAL's exact answer
  std::string key;  // 16 hex digits, see the header comment
  std::optional<AnimateParams> animate = std::nullopt;  // animate jobs
  bool occlude = false;  // occlude jobs: validation_views is the number of metric views
  // Doom jobs: validation_views is the order check's eyes; seed and views are 0 but for our heuristics.
  std::optional<DoomParams> doom = std::nullopt;
  // Drawing jobs of mesh scenes: `scene` is the scene's label (file:PATH as the suite wrote it, or
  // mesh:NAME), scene_params and n are empty, and the seed feeds only the heuristic.
  std::optional<SceneFile> file = std::nullopt;
  JobKind kind() const {
    return op        ? JobKind::Merge
           : animate ? JobKind::Animate
           : occlude ? JobKind::Occlude
           : doom    ? JobKind::Doom
                     : JobKind::Draw;
  }
};
std::string_view job_kind_name(JobKind kind);  // draw, merge, animate, occlude, doom

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

// Hash of the suite's name, every job key and, for a suite file, its text: two reports come from the
// same suite definition exactly when these agree.
std::string definition_hash(const std::string& suite_name, const std::vector<Job>& jobs,
                            std::string_view source_text = {});

// {kind: "draw", scene, scene_params, constant_density, heuristic, heuristic_params, build, shape, seed, n,
// validation_views; a mesh scene's scene_file_hash}: the identity
// printed in reports and regression tables, with the `bspbench build` command that rebuilds the tree.
// A merge job's adds kind "merge", operation, points and operands (each scene with its resolved
// parameters), and its command is the `bspbench merge` that repeats the run. A Doom job's is
// doom_identity (doom_job.h).
nlohmann::json job_identity(const Job& job);

// A merge job's two operands (its pair's, for its size and seed).
std::array<SolidOperand, 2> merge_operands(const Job& job);

// Fills job.key from the other fields (resolving parameters, so defaults count).
void assign_key(Job& job);

// The polygons of a drawing job's scene: generated, or read from its file (once per call), named
// by the job's scene label. Throws InputError for a file that cannot be read or holds no polygons.
Scene job_scene(const Job& job);

// Hash of a file's bytes (16 hex digits); throws InputError naming the file when it cannot be read.
std::string file_hash(const std::string& path);

}  // namespace bsp::sweep
