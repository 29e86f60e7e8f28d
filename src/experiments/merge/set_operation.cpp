#include "experiments/merge/set_operation.h"

#include <string>

#include "common/cpu_time.h"
#include "common/errors.h"
#include "solid/boundary.h"

namespace bsp::experiments {

namespace {

void refuse_self_intersections(const Scene& scene, const ExactSolid& exact) {
  if (const std::size_t n = exact.self_intersecting_pairs(); n > 0)
    throw InputError(scene.name + ": not the boundary of a solid: " + std::to_string(n) + " pairs of faces intersect");
}

SolidBuild timed_build(const Scene& scene, Splitter& splitter, const Box& box, double& cpu_seconds) {
  const double start = thread_cpu_seconds();
  SolidBuild solid = build_solid(scene.polygons, splitter, box);
  cpu_seconds = thread_cpu_seconds() - start;
  return solid;
}

}  // namespace

SetOperationRun run_set_operation(const Scene& a, const Scene& b, SetOp op, Splitter& splitter,
                                  const SolidCheckSettings& settings,
                                  const std::function<void(const SolidOperands&)>& after_merge) {
  SetOperationRun run;
  SolidOperands& o = run.operands;
  o.box = solid_box(bounds(a), bounds(b));
  const double eps = Tolerance::for_extent(o.box.diagonal()).plane_eps;
  require_closed_solid(a.polygons, eps, a.name);
  require_closed_solid(b.polygons, eps, b.name);
  const ExactSolid exact_a(a.polygons), exact_b(b.polygons);
  refuse_self_intersections(a, exact_a);
  refuse_self_intersections(b, exact_b);
  o.a = timed_build(a, splitter, o.box, o.a_cpu_seconds);
  o.b = timed_build(b, splitter, o.box, o.b_cpu_seconds);
  run.result = merge(o.a.solid, o.b.solid, op, &run.stats);
  if (after_merge) after_merge(o);
  run.check = check_set_operation(run.result, exact_a, exact_b, a.polygons, b.polygons, op, settings);
  return run;
}

}  // namespace bsp::experiments
