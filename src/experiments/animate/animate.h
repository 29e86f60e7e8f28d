#pragma once
// Animate runs: dynamic scenes (generators/animation.h) kept as one tree by an update strategy
// (dynamic/updater.h) frame by frame (animation_run.h, the run `bspbench animate` makes). A suite
// block of this kind is an "animations" entry: scene x size x heuristic x strategy x moving-object
// count x speed x seed, all other animation settings the block's. The research question: at which
// moving fraction and speed does each strategy stop beating rebuild? The record is
// analysis/SCHEMA.md's ANIMATE RUN: the frames' sizes, culled cost, the updates' work totals
// (work_*) and the drift from a fresh build at the last drift frame (drift_*) as metrics; the
// checked frames' violations as invariants and validation; the per-frame update CPU times as the
// gated samples (one sample per update, not batches, so the planted slowdown does not apply).
#include <cstdint>
#include <string>
#include <vector>

#include "experiments/kind.h"
#include "experiments/scene_run.h"

namespace bsp::experiments {

struct AnimateBlock final : Block {
  std::vector<std::string> scenes;
  std::vector<std::uint64_t> sizes;
  std::vector<std::string> heuristics;  // empty: every registered heuristic
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

  Jobs expand() const override;
};

// An animate job's animation and update strategy.
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

class AnimateJob final : public Job {
 public:
  AnimateJob(SceneRun scene, AnimateParams animate);
  std::string_view kind() const override { return "animate"; }
  nlohmann::json identity() const override;
  nlohmann::json run(const RunContext& context) const override;
  const SceneRun& scene() const { return scene_; }
  const AnimateParams& params() const { return animate_; }
  // The object trees' heuristic label: halving for torres (its method), else the run's.
  std::string object_heuristic() const;

 private:
  SceneRun scene_;
  AnimateParams animate_;
};

const Kind& animate_kind();

}  // namespace bsp::experiments
