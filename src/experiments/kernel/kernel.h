#pragma once
// Kernel runs: what the float kernel's tolerance does to a tree, measured against the exact kernel
// (tree/exact_build.h) on the same input snapped to the scene's grid, so the two differ only in
// how they decide. A suite block of this kind is a "kernels" entry: scene x size x heuristic x
// seed. The record (analysis/SCHEMA.md, KERNEL RUN) holds, for both kernels: size and shape,
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
// Node planes of the exact tree every input polygon is classified against by both kernels.
inline constexpr std::size_t kClassifyPlanes = 64;

struct KernelBlock final : Block {
  std::vector<std::string> scenes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = kKernelViews;

  Jobs expand() const override;
};

// The comparison's sections of a record (make_record's).
struct KernelComparison {
  nlohmann::json metrics, invariants, validation, timings;
};
// Both kernels on `input`; each splitter builds one tree (the same heuristic and seed twice).
KernelComparison compare_kernels(std::span<const Polygon> input, Splitter& float_splitter, Splitter& exact_splitter,
                                 std::uint32_t views);

class KernelJob final : public Job {
 public:
  explicit KernelJob(SceneRun scene);
  std::string_view kind() const override { return "kernel"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& scene() const { return scene_; }

 private:
  SceneRun scene_;
};

const Kind& kernel_kind();

}  // namespace bsp::experiments
