#pragma once
// What drawing, animate and occlude jobs share: one tree of one scene, built by a heuristic (or by
// Thibault–Naylor insertion) with a seed, and checked from some views. The scene is a generator
// with its parameters (n and seed among them when it takes them), or a mesh: a file:PATH or
// mesh:NAME scene, read once per job and keyed by the hash of the file's bytes, so a changed file
// is another run, and so is the same file under another label. The seed feeds both the scene's
// generator and the heuristic, as in `bspbench build --seed`.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "common/params.h"
#include "experiments/heuristic_choice.h"
#include "scene/scene.h"
#include "tree/tree.h"

namespace bsp {
struct GeneratorInfo;
}

namespace bsp::experiments {

inline constexpr std::string_view kFileScenePrefix = "file:";
bool is_file_scene(std::string_view scene_name);

// A mesh scene's file as opened, and the hash of its bytes (16 hex digits).
struct SceneFile {
  std::string path;
  std::string hash;
};
// Hash of a file's bytes; throws InputError naming the file when it cannot be read.
std::string file_hash(const std::string& path);

struct SceneRun {
  std::string scene;               // the generator's name, or the mesh's label (file:PATH as written, mesh:NAME)
  ParamAssignments scene_params;   // a generator's, with n and seed when it has them; empty for a mesh
  std::optional<SceneFile> file;   // a mesh's
  std::optional<HeuristicChoice> heuristic;  // none for an incremental build
  Shape shape = Shape::Strict;
  std::uint64_t seed = 1;
  std::uint64_t n = 0;             // requested size; 0 when the generator has none, or for a mesh
  std::uint32_t views = 0;         // validation views

  // A generator's run at size n (0: none) and `seed`, which joins its parameters when it has them.
  static SceneRun generated(const GeneratorInfo& g, ParamAssignments params, std::optional<HeuristicChoice> heuristic,
                            Shape shape, std::uint64_t seed, std::uint64_t n, std::uint32_t views);

  bool incremental() const { return !heuristic; }
  // The heuristic's label, or kIncrementalLabel (tree/build.h).
  std::string heuristic_label() const;
  ParamSet heuristic_params() const;
  ParamSet resolved_scene_params() const;  // empty for a mesh

  // Everything that decides the run's results, with the scene given as `scene_text`: its resolved
  // parameters or file hash for the key (key_scene_text), its content for measured identities.
  std::string hash(const std::string& scene_text) const;
  std::string key_scene_text() const;
  // The hash of the generated scene's content, made once per process: sizes are nominal, and a
  // generator may build the same scene at several (architecture's 136-polygon building at 30, 100, 300).
  const std::string& content_hash() const;

  // The polygons: generated, or read from the file (once per call). Throws InputError for a file
  // that cannot be read or holds no polygons.
  Scene make_scene() const;
  // " --scene NAME --n N --scene-param k=v" or " --input FILE", as the commands take the scene.
  std::string scene_arguments() const;
  // {kind, scene, scene_params, constant_density, heuristic, heuristic_params, build, shape, seed,
  // n, validation_views, command: the `bspbench build` that rebuilds the tree; a mesh's
  // scene_file_hash}.
  nlohmann::json identity(std::string_view kind) const;
};

}  // namespace bsp::experiments
