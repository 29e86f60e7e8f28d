#pragma once
// The options shared by every command that builds a tree:
//   --scene NAME [--n N] [--seed S] [--scene-param k=v]...  |  --input FILE
//   --heuristic NAME [--param k=v]... [--shape strict|coarse] [--incremental [--order given|shuffled]]
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "cli/args.h"
#include "common/params.h"
#include "scene/scene.h"
#include "tree/build.h"

namespace bsp::cli {

inline constexpr std::string_view kSceneUsage =
    "(--scene NAME [--n N] [--seed S] [--scene-param k=v]... | --input FILE)";
inline constexpr std::string_view kTreeUsage =
    "--heuristic NAME [--param k=v]... [--shape strict|coarse] [--incremental [--order given|shuffled]]";

struct TreeArgs {
  std::string heuristic;
  ParamAssignments params;
  BuildOptions options;
  std::uint64_t seed = 1;  // the scene's seed, or --seed for files; feeds the heuristic's randomness
};

// `seed` receives --seed (default 1): the scene's seed for a generator, the heuristic's for any run.
Scene scene_from_args(Args& args, std::uint64_t& seed);
TreeArgs tree_args_from(Args& args, std::uint64_t seed);
// --shape, --incremental, --order: the build options of a run with `seed` (tree_args_from's part
// that does not name a heuristic, for commands that run several).
BuildOptions build_options_from(Args& args, std::uint64_t seed);
// The seed of a shuffled incremental build's insertion order in a run with `seed`.
std::uint64_t insertion_order_seed(std::uint64_t seed);
Tree build_from_args(const Scene& scene, const TreeArgs& t);
// Identifies a run in every JSON the CLI writes: scene name, params, hash and bounds; heuristic,
// its resolved params, shape, build order, seed.
nlohmann::json describe_run(const Scene& scene, const TreeArgs& t);

}  // namespace bsp::cli
