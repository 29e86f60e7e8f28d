#pragma once
// A set operation on two closed solids by merging their BSP trees [Naylor1990], proved against
// CGAL: the one pipeline behind `bspbench merge` and the sweep's merge runs. Both operands must be
// closed solids whose faces do not intersect; one splitter builds both solid trees over their common
// box (so the same seed gives the same trees as the command); the trees are merged by the
// operation and reduced; the result is checked against CGAL's exact answer (validate/solid_check.h:
// points against exact side-of-mesh answers, the volume against corefinement, the boundary closed).
#include <functional>

#include "scene/scene.h"
#include "solid/exact_merge.h"
#include "solid/merge.h"
#include "solid/solid_build.h"
#include "split/splitter.h"
#include "validate/exact_solid_check.h"
#include "validate/solid_check.h"

namespace bsp::experiments {

struct SolidOperands {
  Box box;
  SolidBuild a, b;
  double a_cpu_seconds = 0, b_cpu_seconds = 0;  // thread CPU time of each build, labels included
};

struct SetOperationRun {
  SolidOperands operands;
  MergeStats stats;  // of the first merge, the one proved
  SolidTree result;
  SolidCheck check;
};

// Throws InputError naming the scene when an operand is not a closed solid or its faces intersect.
// `after_merge`, when given, runs between the merge and the proof with the operand trees: where a
// run times repeated merges without timing the proof.
SetOperationRun run_set_operation(const Scene& a, const Scene& b, SetOp op, Splitter& splitter,
                                  const SolidCheckSettings& settings,
                                  const std::function<void(const SolidOperands&)>& after_merge = {});

// The same in the exact kernel: both operands snapped to the grid of their common box (one space),
// built as exact solid trees, merged exactly, and the result proved at grid points, by its exact
// volume against CGAL's exact corefinement of the same snapped operands, and by its exact closure
// (validate/exact_solid_check.h). Besides the float path's refusals, throws InputError when the
// snapped operands are not closed or their faces intersect (snapping can make faces meet).
struct ExactSolidOperands {
  std::unique_ptr<ExactSolidSpace> space;
  ExactSolidBuild a, b;
  double a_cpu_seconds = 0, b_cpu_seconds = 0;
};

struct ExactSetOperationRun {
  ExactSolidOperands operands;
  MergeStats stats;
  ExactSolidTree result;
  std::vector<PlanePolygon> boundary;
  ExactSolidCheck check;
};

ExactSetOperationRun run_exact_set_operation(const Scene& a, const Scene& b, SetOp op, Splitter& splitter,
                                             const SolidCheckSettings& settings,
                                             const std::function<void(ExactSolidOperands&)>& after_merge = {});

}  // namespace bsp::experiments
