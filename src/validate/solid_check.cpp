#include "validate/solid_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "common/rng.h"
#include "solid/cells.h"

namespace bsp {

Vec3 near_surface_point(std::span<const Polygon> polys, Rng& rng, double reach) {
  const Polygon& p = polys[rng.below(polys.size())];
  const std::size_t k = 1 + rng.below(p.verts.size() - 2);
  double u = rng.uniform(), v = rng.uniform();
  if (u + v > 1) u = 1 - u, v = 1 - v;
  const Vec3 a = p.verts[0].p, b = p.verts[k].p, c = p.verts[k + 1].p;
  const Vec3 n = normalize(cross(b - a, c - a));
  return a + (b - a) * u + (c - a) * v + n * rng.uniform(-reach, reach);
}

bool in_result(SetOp op, bool in_a, bool in_b) {
  switch (op) {
    case SetOp::Union: return in_a || in_b;
    case SetOp::Intersection: return in_a && in_b;
    case SetOp::Difference: return in_a && !in_b;
    case SetOp::SymmetricDifference: return in_a != in_b;
  }
  return false;
}

SolidCheck check_set_operation(const SolidTree& result, const ExactSolid& a, const ExactSolid& b,
                               std::span<const Polygon> a_polys, std::span<const Polygon> b_polys, SetOp op,
                               const SolidCheckSettings& settings) {
  SolidCheck c;
  Box box;
  for (const auto* polys : {&a_polys, &b_polys})
    for (const Polygon& p : *polys)
      for (const Vertex& v : p.verts) box.add(v.p);
  const Box sample_box = box.enlarged(0.01);
  const double eps = result.tol.plane_eps;
  Rng rng(stream_seed(settings.seed, 0x5011d));
  for (std::uint64_t i = 0; i < settings.points; ++i) {
    Vec3 p;
    if (i % 2 == 0) {
      const Vec3 lo = sample_box.lo, hi = sample_box.hi;
      p = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
    } else {
      p = near_surface_point(i % 4 == 1 ? a_polys : b_polys, rng, settings.near_distance * box.diagonal());
    }
    ++c.points;
    const ExactSide sa = a.side(p), sb = b.side(p);
    if (sa == ExactSide::Boundary || sb == ExactSide::Boundary) {
      ++c.on_operand;
      continue;
    }
    const bool truth = in_result(op, sa == ExactSide::Inside, sb == ExactSide::Inside);
    const PointClass got = classify_point(result, p);
    const bool agrees = got == (truth ? PointClass::In : PointClass::Out);
    if (std::min(a.distance(p), b.distance(p)) <= eps) {
      ++c.within_eps;
      c.within_eps_disagree += !agrees;
      continue;
    }
    ++c.compared;
    c.mismatches += !agrees;
  }
  c.tree_volume = solid_volume(result);
  const auto start = std::chrono::steady_clock::now();
  try {
    c.exact_volume = corefine(a, b, op).volume;
  } catch (const std::runtime_error& e) {
    c.corefine_error = e.what();
    c.exact_volume = std::numeric_limits<double>::quiet_NaN();
  }
  c.corefine_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double scale = std::max(std::abs(c.exact_volume), 1e-300);
  c.volume_relative_error = std::abs(c.tree_volume - c.exact_volume) / scale;
  c.boundary = check_boundary(solid_boundary(result), eps);
  c.boundary_volume_relative_error = std::abs(c.boundary.volume - c.tree_volume) / std::max(std::abs(c.tree_volume), 1e-300);
  return c;
}

nlohmann::json to_json(const SolidCheck& c) {
  return {{"points", c.points},
          {"on_operand_surface", c.on_operand},
          {"within_plane_eps", c.within_eps},
          {"within_plane_eps_disagree", c.within_eps_disagree},
          {"compared", c.compared},
          {"mismatches", c.mismatches},
          {"tree_volume", c.tree_volume},
          {"corefine_volume", c.exact_volume},
          {"volume_relative_error", c.volume_relative_error},
          {"corefine_seconds", c.corefine_seconds},
          {"corefine_error", c.corefine_error},
          {"boundary",
           {{"faces", c.boundary.faces},
            {"vertices", c.boundary.vertices},
            {"t_junctions_split", c.boundary.t_junctions},
            {"dropped_faces", c.boundary.dropped_faces},
            {"edges", c.boundary.edges.edges},
            {"border_edges", c.boundary.edges.border_edges},
            {"repeated_directed_edges", c.boundary.edges.repeated_directed},
            {"volume", c.boundary.volume},
            {"volume_relative_error", c.boundary_volume_relative_error}}},
          {"ok", c.ok(kVolumeRelativeTolerance)}};
}

nlohmann::json to_json(const SolidSize& s) {
  return {{"nodes", s.nodes}, {"in_leaves", s.in_leaves}, {"out_leaves", s.out_leaves}, {"depth", s.depth}};
}

nlohmann::json to_json(const MergeStats& s) {
  return {{"partition_calls", s.partition_calls},
          {"partition_nodes", s.partition_nodes},
          {"shp_splits", s.shp_splits},
          {"merge_nodes", s.merge_nodes},
          {"cell_ops", s.cell_ops},
          {"complement_nodes", s.complement_nodes},
          {"inconsistent", s.inconsistent},
          {"pruned", s.pruned},
          {"compactions", s.compactions},
          {"compacted_nodes", s.compacted_nodes},
          {"before", to_json(s.before)},
          {"after", to_json(s.after)},
          {"merge_seconds", s.merge_seconds},
          {"reduce_seconds", s.reduce_seconds}};
}

}  // namespace bsp
