#pragma once
// Kernel runs: what the float kernel's tolerance does to a tree, measured against the exact kernel
// (tree/exact_build.h) on the same input snapped to the scene's grid, so the two differ only in
// how they decide. A suite block of this kind is a "kernels" entry: scene x size x heuristic x
// seed x the float kernel's tolerance x a perturbation of the input, so a block can sweep
// plane_eps (1e-12 ... 1e-4 of the diagonal) and the input's noise (1e-15 ... 1e-6 of it) and show
// where each scene starts to go wrong. The record (analysis/SCHEMA.md, KERNEL RUN) holds, for both
// kernels: size and shape,
// what the float kernel dropped, each tree's order checked from `views` eyes (violations, ties,
// pairs judged); how often the float kernel classifies a polygon against a plane differently
// from the exact decision; how the exact kernel's predicates were decided; the build times.
// `bspbench kernel` runs one job's comparison and prints it.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "experiments/kind.h"
#include "experiments/scene_run.h"
#include "geometry/polygon.h"
#include "split/splitter.h"

namespace bsp::experiments {

inline constexpr std::uint32_t kKernelViews = 4;
// Bounds of a run's tolerance and perturbation, relative to the scene's diagonal: below 1e-15 a
// tolerance is under the rounding of coordinates, above 1e-2 it swallows the scene.
inline constexpr double kMinRelative = 1e-15, kMaxRelative = 1e-2;

// What a comparison varies besides the scene and the heuristic.
struct KernelSettings {
  std::uint32_t views = kKernelViews;
  double plane_eps_relative = kPlaneEpsRelative;  // the float kernel's tolerance
  // Each vertex moves by up to this times the diagonal per coordinate, the same for every copy of
  // a point (the offset is a hash of its position and `seed`), before either kernel sees it.
  double perturbation = 0;
  std::uint64_t seed = 1;
};
// Node planes of the exact tree every input polygon is classified against by both kernels.
inline constexpr std::size_t kClassifyPlanes = 64;

struct KernelBlock final : Block {
  std::vector<std::string> scenes;
  // mesh:NAME scenes, each run once per heuristic, seed and setting; one not in the mesh cache is
  // skipped with a line on stderr (the cache is filled by generators/fetch_meshes.sh), so a suite
  // naming meshes runs where none were fetched.
  std::vector<std::string> meshes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = kKernelViews;
  std::vector<double> plane_eps = {kPlaneEpsRelative};
  std::vector<double> perturbations = {0.0};

  Jobs expand() const override;
};

// The comparison's sections of a record (make_record's).
struct KernelComparison {
  nlohmann::json metrics, invariants, validation, timings;
};
// Both kernels on `input` (perturbed as `settings` says); each splitter builds one tree (the same
// heuristic and seed twice).
KernelComparison compare_kernels(std::span<const Polygon> input, Splitter& float_splitter, Splitter& exact_splitter,
                                 const KernelSettings& settings);
// The input as compare_kernels perturbs it.
std::vector<Polygon> perturbed(std::span<const Polygon> input, double relative, std::uint64_t seed);

class KernelJob final : public Job {
 public:
  KernelJob(SceneRun scene, double plane_eps_relative, double perturbation);
  std::string_view kind() const override { return "kernel"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& scene() const { return scene_; }

 private:
  SceneRun scene_;
  double plane_eps_relative_, perturbation_;
};

const Kind& kernel_kind();

}  // namespace bsp::experiments
