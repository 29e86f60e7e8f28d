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

ExactSetOperationRun run_exact_set_operation(const Scene& a, const Scene& b, SetOp op, Splitter& splitter,
                                             const SolidCheckSettings& settings,
                                             const std::function<void(ExactSolidOperands&)>& after_merge) {
  ExactSetOperationRun run;
  ExactSolidOperands& o = run.operands;
  const Box box = solid_box(bounds(a), bounds(b));
  const double eps = Tolerance::for_extent(box.diagonal()).plane_eps;
  require_closed_solid(a.polygons, eps, a.name);
  require_closed_solid(b.polygons, eps, b.name);
  o.space = ExactSolidSpace::for_box(box);
  require_snapped_solid(a.polygons, o.space->grid(), a.name);
  require_snapped_solid(b.polygons, o.space->grid(), b.name);
  double start = thread_cpu_seconds();
  o.a = build_exact_solid(a.polygons, splitter, *o.space);
  o.a_cpu_seconds = thread_cpu_seconds() - start;
  start = thread_cpu_seconds();
  o.b = build_exact_solid(b.polygons, splitter, *o.space);
  o.b_cpu_seconds = thread_cpu_seconds() - start;
  run.result = merge(o.a.solid, o.b.solid, *o.space, op, &run.stats);
  if (after_merge) after_merge(o);
  run.boundary = exact_solid_boundary(run.result, *o.space);
  run.check = check_exact_set_operation(run.result, *o.space, run.boundary, a.polygons, b.polygons, op, settings);
  return run;
}

}  // namespace bsp::experiments
