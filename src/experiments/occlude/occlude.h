#pragma once
// Occlude runs: occlusion culling by beam tracing (cull/occlusion.h) from `views` metric views of a
// scene's tree, each view proved by Embree primary rays (occlusion_run.h, the view `bspbench
// occlude` runs). A suite block of this kind is an "occlusions" entry: scene x size x heuristic x
// seed. The record is analysis/SCHEMA.md's OCCLUDE RUN: the views' sums (emitted, frustum_culled,
// seen_by_embree and the culling's counters) with the mean ratios as metrics; the tree's invariants;
// the Embree proof as validation (violations: rays whose first hit was culled); timed batches of
// culling every view as the gated samples.
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/kind.h"
#include "experiments/scene_run.h"

namespace bsp::experiments {

struct OccludeBlock final : Block {
  std::vector<std::string> scenes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic
  std::vector<std::uint64_t> seeds;
  std::uint32_t views = 4;

  Jobs expand() const override;
};

class OccludeJob final : public Job {
 public:
  explicit OccludeJob(SceneRun scene);
  std::string_view kind() const override { return "occlude"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& scene() const { return scene_; }

 private:
  SceneRun scene_;  // views: the metric views culled from
};

const Kind& occlude_kind();

}  // namespace bsp::experiments
