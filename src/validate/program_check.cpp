// Notation: a leaf's side of a point comes from CGAL's exact predicates (validate/exact_solid.h);
// the truth of a point is the program evaluated on those sides, a stack of booleans.
#include "validate/program_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "common/rng.h"
#include "solid/cells.h"
#include "validate/exact_measure.h"
#include "validate/exact_solid.h"
#include "validate/exact_solid_check.h"

namespace bsp {

namespace {

// The program's answer at a point, from its leaves' exact sides.
class ProgramTruth {
 public:
  ProgramTruth(std::span<const std::vector<Polygon>> leaves, std::span<const std::vector<Polygon>> hulls,
               std::span<const Step> steps)
      : steps_(steps) {
    for (const auto& leaf : leaves) leaves_.push_back(std::make_unique<ExactSolid>(leaf));
    for (const auto& hull : hulls) hulls_.push_back(hull.empty() ? nullptr : std::make_unique<ExactSolid>(hull));
  }

  // Inside or not; nullopt when the point lies on a leaf's or hull's surface.
  std::optional<bool> inside(const Vec3& p) const {
    std::vector<bool> stack;
    std::size_t hull = 0;
    for (const Step& s : steps_) {
      if (s.kind == StepKind::Leaf || s.kind == StepKind::Hull) {
        const ExactSolid* solid = s.kind == StepKind::Leaf ? leaves_[s.count].get() : hulls_[hull++].get();
        if (s.kind == StepKind::Hull) stack.resize(stack.size() - s.count);
        const ExactSide side = solid ? solid->side(p) : ExactSide::Outside;  // no hull: the empty solid
        if (side == ExactSide::Boundary) return std::nullopt;
        stack.push_back(side == ExactSide::Inside);
        continue;
      }
      if (s.kind == StepKind::Empty || s.count == 0) {
        stack.push_back(false);
        continue;
      }
      const auto first = stack.end() - s.count;
      bool r = *first;
      for (auto it = first + 1; it != stack.end(); ++it)
        r = s.kind == StepKind::Union ? (r || *it) : s.kind == StepKind::Intersection ? (r && *it) : (r && !*it);
      stack.erase(first, stack.end());
      stack.push_back(r);
    }
    return !stack.empty() && stack.back();
  }
  // Distance to the nearest leaf or hull surface (rounded constructions).
  double distance(const Vec3& p) const {
    double d = std::numeric_limits<double>::infinity();
    for (const auto* set : {&leaves_, &hulls_})
      for (const auto& s : *set)
        if (s) d = std::min(d, s->distance(p));
    return d;
  }

 private:
  std::span<const Step> steps_;
  std::vector<std::unique_ptr<ExactSolid>> leaves_, hulls_;
};

// A point near a random face of a random leaf.
Vec3 near_surface(std::span<const std::vector<Polygon>> leaves, Rng& rng, double reach) {
  return near_surface_point(leaves[rng.below(leaves.size())], rng, reach);
}

Box bounds_of(std::span<const std::vector<Polygon>> leaves) {
  Box box;
  for (const auto& leaf : leaves)
    for (const Polygon& p : leaf)
      for (const Vertex& v : p.verts) box.add(v.p);
  return box;
}

// Half the points uniform in the leaves' box, half near their surfaces; `classify` says whether
// the result agrees with the truth, `near` whether the point is too near a surface to compare.
template <class Classify, class Near>
void sample(ProgramCheck& c, std::span<const std::vector<Polygon>> leaves, const ProgramTruth& truth,
            const SolidCheckSettings& settings, std::uint64_t stream, Classify classify, Near near, bool round) {
  if (leaves.empty()) return;
  const Box box = bounds_of(leaves).enlarged(0.01);
  Rng rng(stream_seed(settings.seed, stream));
  for (std::uint64_t i = 0; i < settings.points; ++i) {
    Vec3 p = i % 2 == 0 ? Vec3{rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y), rng.uniform(box.lo.z, box.hi.z)}
                        : near_surface(leaves, rng, settings.near_distance * box.diagonal());
    if (round) p = {std::nearbyint(p.x), std::nearbyint(p.y), std::nearbyint(p.z)};
    ++c.points;
    const std::optional<bool> in = truth.inside(p);
    if (!in) {
      ++c.on_operand;
      continue;
    }
    const bool agrees = classify(p, *in);
    if (near(p)) {
      ++c.within_eps;
      c.within_eps_disagree += !agrees;
      continue;
    }
    ++c.compared;
    c.mismatches += !agrees;
  }
}

// CGAL's corefinement, each step's operands combined as a balanced tree (the same solid, without
// the quadratic cost of re-cutting a growing result once per operand); where it refuses (an intermediate result is not a manifold
// mesh: parts touching along an edge), Nef polyhedra, which take any solid.
void corefine_volume(ProgramCheck& c, std::span<const std::vector<Polygon>> leaves, const std::vector<std::vector<Polygon>>& hulls,
                     std::span<const Step> steps, double unit) {
  ExactProgramVolume r = exact_corefine_program(leaves, steps, FoldOrder::Balanced, &hulls);
  c.reference = "corefine";
  if (!r.error.empty()) {
    c.corefine_refused = r.error;
    r = exact_nef_program(leaves, steps, FoldOrder::Balanced, &hulls);
    c.reference = "nef";
  }
  c.corefine_error = r.error;
  c.corefine_volume_exact = r.volume;
  c.corefine_volume = r.volume_double * unit * unit * unit;
  c.corefine_seconds = r.seconds;
  c.corefine_operations = r.operations;
  const double scale = std::max(std::abs(c.corefine_volume), 1e-300);
  c.volume_relative_error = r.error.empty() ? std::abs(c.volume - c.corefine_volume) / scale : std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::vector<Polygon>> in_grid_units(std::span<const std::vector<Polygon>> meshes, const Grid& grid) {
  std::vector<std::vector<Polygon>> out;
  for (const auto& m : meshes) out.push_back(grid_unit_polygons(m, grid));
  return out;
}

}  // namespace

ProgramCheck check_program(const SolidTree& result, const LoopPool& boundary, std::span<const std::vector<Polygon>> leaves,
                           std::span<const std::vector<Polygon>> hulls, std::span<const Step> steps,
                           const SolidCheckSettings& settings) {
  ProgramCheck c;
  const ProgramTruth truth(leaves, hulls, steps);
  const double eps = result.tol.plane_eps;
  sample(
      c, leaves, truth, settings, 0xc5601,
      [&](const Vec3& p, bool in) { return classify_point(result, p) == (in ? PointClass::In : PointClass::Out); },
      [&](const Vec3& p) { return truth.distance(p) <= eps; }, false);
  c.volume = solid_volume(result);
  const BoundaryCheck b = check_boundary(boundary, eps);
  c.boundary_faces = b.faces;
  c.border_edges = b.edges.border_edges;
  corefine_volume(c, leaves, std::vector<std::vector<Polygon>>(hulls.begin(), hulls.end()), steps, 1.0);
  return c;
}

ProgramCheck check_exact_program(const ExactSolidTree& result, const ExactSolidSpace& space,
                                 std::span<const PlanePolygon> boundary, std::span<const std::vector<Polygon>> leaves,
                                 std::span<const std::vector<Polygon>> hulls, std::span<const Step> steps,
                                 const SolidCheckSettings& settings) {
  ProgramCheck c;
  c.exact = true;
  const std::vector<std::vector<Polygon>> grid_leaves = in_grid_units(leaves, space.grid());
  const std::vector<std::vector<Polygon>> grid_hulls = in_grid_units(hulls, space.grid());
  const ProgramTruth truth(grid_leaves, grid_hulls, steps);
  const auto as_grid = [](const Vec3& p) { return GridPoint{std::llround(p.x), std::llround(p.y), std::llround(p.z)}; };
  sample(
      c, grid_leaves, truth, settings, 0xc5602,
      [&](const Vec3& p, bool in) { return classify_point(result, space, as_grid(p)) == (in ? PointClass::In : PointClass::Out); },
      [](const Vec3&) { return false; }, true);
  const ExactBoundaryCheck b = check_exact_boundary(boundary);
  const double step = space.grid().step();
  c.volume_exact = b.volume;
  c.volume = b.volume_double * step * step * step;
  c.boundary_faces = b.faces;
  c.border_edges = b.border_segments;
  corefine_volume(c, grid_leaves, grid_hulls, steps, step);
  return c;
}

nlohmann::json to_json(const ProgramCheck& c) {
  nlohmann::json j = {{"points", c.points},
                      {"on_operand_surface", c.on_operand},
                      {"within_plane_eps", c.within_eps},
                      {"within_plane_eps_disagree", c.within_eps_disagree},
                      {"compared", c.compared},
                      {"mismatches", c.mismatches},
                      {"volume", c.volume},
                      {"corefine_volume", c.corefine_volume},
                      {"volume_relative_error", c.volume_relative_error},
                      {"corefine_seconds", c.corefine_seconds},
                      {"corefine_operations", c.corefine_operations},
                      {"corefine_error", c.corefine_error},
                      {"reference", c.reference},
                      {"corefine_refused", c.corefine_refused},
                      {"boundary_faces", c.boundary_faces},
                      {"border_edges", c.border_edges},
                      {"ok", c.ok()}};
  if (c.exact) {
    j["volume_exact"] = c.volume_exact;
    j["corefine_volume_exact"] = c.corefine_volume_exact;
  }
  return j;
}

}  // namespace bsp
