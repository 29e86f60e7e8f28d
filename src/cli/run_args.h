#pragma once
// The options shared by every command that builds a tree:
//   --scene NAME [--n N] [--seed S] [--scene-param k=v]...  |  --input FILE
//   (--heuristic NAME [--param k=v]... | --incremental [--order given|shuffled]) [--shape strict|coarse|leafy]
// An incremental build consults no heuristic (tree/build_incremental.h: the insertion order picks
// the planes), so --heuristic with --incremental is a usage error and the run is labelled with the
// heuristic "incremental" in every JSON.
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "cli/args.h"
#include "common/params.h"
#include "scene/scene.h"
#include "tree/build.h"
#include "tree/exact_build.h"

namespace bsp::cli {

inline constexpr std::string_view kSceneUsage =
    "(--scene NAME [--n N] [--seed S] [--scene-param k=v]... | --input FILE)";
inline constexpr std::string_view kTreeUsage =
    "(--heuristic NAME [--param k=v]... | --incremental [--order given|shuffled]) [--shape strict|coarse|leafy]";

inline const OptionHelps kSceneOptions = {
    {"--scene NAME", "a generated scene (bspbench scenes lists them) or mesh:NAME"},
    {"--n N", "the generator's polygon count parameter"},
    {"--seed S", "seed of the scene and of the heuristic's randomness (default 1)"},
    {"--scene-param k=v", "set another generator parameter; repeatable"},
    {"--input FILE", "read the polygons from a mesh file (OBJ, OFF, PLY, STL) instead of --scene"}};
inline const OptionHelps kBuildModeOptions = {
    {"--shape strict|coarse|leafy", "one plane per node, convex sets of polygons in the leaves, or every polygon in a convex leaf (default strict)"},
    {"--incremental", "insert the polygons one at a time (Thibault-Naylor); no heuristic is consulted"},
    {"--order given|shuffled", "insertion order of an --incremental build: as read, or seeded shuffle"}};
inline const OptionHelps kTreeOptions = {
    {"--heuristic NAME", "the splitting-plane heuristic (bspbench heuristics lists them)"},
    {"--param k=v", "set a heuristic parameter; repeatable"},
    kBuildModeOptions[0], kBuildModeOptions[1], kBuildModeOptions[2]};

inline const OptionHelp kKernelOption = {
    "--kernel float|exact",
    "the geometry: doubles with the tolerance plane_eps (default), or exact plane-based geometry on the scene's grid"};
inline constexpr std::string_view kKernelUsage = "[--kernel float|exact]";

struct TreeArgs {
  std::string heuristic;
  ParamAssignments params;
  BuildOptions options;
  std::uint64_t seed = 1;  // the scene's seed, or --seed for files; feeds the heuristic's randomness
  Kernel kernel = Kernel::Float;  // read by commands that take --kernel (kernel_from)
};

// `seed` receives --seed (default 1): the scene's seed for a generator, the heuristic's for any run.
Scene scene_from_args(Args& args, std::uint64_t& seed);
TreeArgs tree_args_from(Args& args, std::uint64_t seed);
// --shape, --incremental, --order: the build options of a run with `seed` (tree_args_from's part
// that does not name a heuristic, for commands that run several).
BuildOptions build_options_from(Args& args, std::uint64_t seed);
Tree build_from_args(const Scene& scene, const TreeArgs& t);
// --kernel float|exact (default float); exact refuses --incremental and --shape leafy in `t`, and
// a 2D scene.
Kernel kernel_from(Args& args, const TreeArgs& t, const Scene& scene);
ExactTree build_exact_from_args(const Scene& scene, const TreeArgs& t);
// --shape strict|coarse|leafy alone (default strict), for commands whose builds are never incremental.
Shape shape_from(Args& args);
// A catalog scene or mesh:NAME with "k=v" parameters, else a mesh file (which takes none: a
// UsageError naming `option`); checked with check_scene.
Scene scene_or_file(const std::string& spec, const std::vector<std::string>& params, std::string_view option);
// Identifies a run in every JSON the CLI writes: scene name, params, hash and bounds; heuristic,
// its resolved params, shape, build order, seed; the kernel only when it is not float.
nlohmann::json describe_run(const Scene& scene, const TreeArgs& t);

}  // namespace bsp::cli
