#pragma once
// Sweep suites: named sets of runs (scene x size x heuristic x shape x seed, solid pair x size x
// heuristic x set operation x seed for merges, Doom map x heuristic x seed beside node builders).
// A suite names no heuristic and, in its main block, no scene: it takes every entry of the
// registries, so a heuristic or generator added there is swept without further wiring. Sizes are
// the generators' `n` parameter; a generator without one runs once at its defaults, and a size
// outside a generator's `n` range is skipped for it. A mesh (a file or mesh:NAME) has no size: it
// runs once per heuristic, shape and seed, the seed feeding only the heuristic.
//
// Every suite is a JSON file (suite_file.h); the built-in ones are analysis/suites/*.json (suite_catalog.h).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"
#include "solid/merge.h"
#include "tree/tree.h"

namespace bsp::sweep {

// How much ray-cast validation each run gets (validate_tree's view count); bigger scenes get fewer
// views so a suite stays within its time budget.
struct ValidationPlan {
  std::uint32_t views = 0;            // views for scenes up to `reduce_above` polygons; 0 = no validation
  std::uint64_t reduce_above = 0;     // polygon count past which `reduced_views` apply
  std::uint32_t reduced_views = 0;
  std::uint32_t views_for(std::uint64_t n) const { return n > reduce_above ? reduced_views : views; }
};

// Sizes for one scene whose cost grows much faster than n log n (Omega(n^2) fragments), in place of
// the block's common sizes.
struct SceneSizes {
  std::string scene;
  std::vector<std::uint64_t> sizes;
};

// A scene of a drawing block: a generator by name, with parameters other than n and seed (those come
// from the block's sizes and seeds); a mesh of the cache, "mesh:NAME" (generators/mesh_scenes.h); or
// a mesh file, "file:PATH", PATH as its suite wrote it.
struct SceneSpec {
  std::string name;
  ParamAssignments params = {};  // generators only
  std::string path = {};  // a file scene's file as opened (PATH resolved against the suite's directory)
  // Implicit, so a block lists bare generator names as plain strings.
  SceneSpec(std::string scene) : name(std::move(scene)) {}
  SceneSpec(const char* scene) : name(scene) {}
  SceneSpec(std::string scene, ParamAssignments scene_params, std::string file_path)
      : name(std::move(scene)), params(std::move(scene_params)), path(std::move(file_path)) {}
};

inline constexpr std::string_view kFileScenePrefix = "file:";
bool is_file_scene(std::string_view scene_name);

struct SuiteBlock {
  // Empty: every generator of the catalog but the closed solids (generators/solids.cpp), which are
  // the operands of set operations (bspbench merge) rather than scenes to draw.
  std::vector<SceneSpec> scenes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic; ignored when incremental
  std::vector<std::uint64_t> sizes;
  std::vector<SceneSizes> scene_sizes;  // overrides `sizes` for the scenes named
  std::vector<std::uint64_t> seeds;
  std::vector<Shape> shapes;
  ValidationPlan validation;
  // One incremental build (tree/build_incremental.h, seeded shuffled order) per scene, size, shape
  // and seed instead of one build per heuristic: it consults no heuristic, so it runs once.
  bool incremental = false;
};

// Set operations on solid pairs (generators/solid_pairs.h): one merge job per pair, size, heuristic,
// operation and seed. Each job builds both operands' solid trees with the heuristic, merges them,
// times the merge, and proves the result against CGAL (validate/solid_check.h).
struct MergeBlock {
  std::vector<std::string> pairs;       // empty: every pair
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<SetOp> ops;               // empty: union, intersection, difference and xor
  std::vector<std::uint64_t> sizes;     // polygons per operand, within the pair's range; unsized pairs run once
  std::vector<std::uint64_t> seeds;
  std::uint64_t points = 0;             // classified against CGAL's exact answer per run
};

// Dynamic scenes (generators/animation.h, dynamic/updater.h): one animate job per scene, size,
// heuristic, update strategy, moving-object count, speed and seed, all other animation settings the
// block's. The research question: at which moving fraction and speed does each strategy stop
// beating rebuild?
struct AnimateBlock {
  std::vector<std::string> scenes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;
  std::vector<std::string> strategies;  // empty: every strategy
  std::vector<std::uint32_t> moving;
  std::vector<double> speeds;
  std::vector<std::uint64_t> seeds;
  std::uint32_t frames = 100;
  std::string object = "sphere";
  std::uint64_t object_n = 80;
  double size = 0.04, spin = 0.02;
  std::uint32_t check_every = 10, drift_every = 0;
  std::uint32_t views = 2;  // Embree order check views per checked frame
};

// Occlusion culling by beam tracing (cull/occlusion.h): one occlude job per scene, size, heuristic
// and seed, culling from `views` metric views, each proved by Embree primary rays.
struct OccludeBlock {
  std::vector<std::string> scenes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = 4;
};

// Doom maps (sweep/doom_job.h): our leafy trees beside the external node builders and the nodes the
// WAD shipped with, on the same maps, measured and proved alike (sweep/doom_run.h). One job per
// IWAD, map, heuristic and seed; one per IWAD, map and external builder, and one for the shipped
// nodes, whatever the seeds (they consult none).
struct DoomBlock {
  std::vector<std::string> iwads;  // file names in the Doom data directory (doom_data_dir())
  std::vector<std::string> maps;   // empty: every map of each IWAD
  // Labels: registered names, NAME:k=v,k=v variants as in the other blocks, or Doom preset names
  // (doom_presets()); empty: every registered heuristic and every preset.
  std::vector<std::string> heuristics;
  std::vector<std::string> builders;  // external node builders (sweep/node_builders.h): zdbsp, glbsp
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = 4;  // eyes of the Embree order check of our trees
};

// A suite a user wrote (suite_file.h): the file as named on the command line, and its text, whose
// hash joins the suite's definition so an edited file never resumes a journal of the old one.
struct SuiteSource {
  std::string path;
  std::string text;
};

struct Suite {
  std::string name;
  std::string summary;  // one line, with the measured run time
  std::vector<SuiteBlock> blocks;
  std::vector<MergeBlock> merges = {};
  std::vector<AnimateBlock> animations = {};
  std::vector<OccludeBlock> occlusions = {};
  std::vector<DoomBlock> doom = {};
  SuiteSource source = {};  // empty for the built-in suites
};


}  // namespace bsp::sweep
