#pragma once
// Proof of a set operation's result against exact geometry: point membership by CGAL's exact
// side-of-mesh predicates on each operand, combined by the operation; the result's volume against
// CGAL's corefinement; and the result's boundary closed after welding.
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "common/rng.h"
#include "geometry/polygon.h"
#include "solid/boundary.h"
#include "solid/merge.h"
#include "validate/exact_solid.h"

namespace bsp {

struct SolidCheckSettings {
  std::uint64_t points = 100000;  // half uniform in the operands' bounding box, half near their surfaces
  std::uint64_t seed = 1;
  // Near-surface points lie within this fraction of the box diagonal of a random surface point.
  double near_distance = 1e-3;
};

struct SolidCheck {
  std::uint64_t points = 0;
  std::uint64_t on_operand = 0;     // exactly on an operand's surface: no side to compare
  std::uint64_t within_eps = 0;     // within plane_eps of an operand's surface: counted apart
  std::uint64_t within_eps_disagree = 0;  // of those, where the tree's answer differs
  std::uint64_t compared = 0;       // everything else
  std::uint64_t mismatches = 0;     // of the compared: the tree says otherwise (On included)
  double tree_volume = 0;           // sum of IN cells
  double exact_volume = 0;          // CGAL corefinement's result
  double volume_relative_error = 0;
  double corefine_seconds = 0;
  std::string corefine_error;       // why CGAL gave no volume (then the volume check fails)
  BoundaryCheck boundary;
  double boundary_volume_relative_error = 0;  // the welded boundary's volume against tree_volume
  bool ok(double volume_tolerance) const {
    return mismatches == 0 && corefine_error.empty() && volume_relative_error <= volume_tolerance && boundary.edges.closed() &&
           boundary_volume_relative_error <= volume_tolerance;
  }
};

// A point on a random face of the polygons (uniform in the face's fan triangle), pushed off it along
// the face's normal by up to `reach` either way: where the proofs look for misclassified points.
Vec3 near_surface_point(std::span<const Polygon> polys, Rng& rng, double reach);

// Whether a point inside (or not) each operand is inside a op b: the truth both proofs compare with.
bool in_result(SetOp op, bool in_a, bool in_b);

// The result must be a op b. Points are drawn deterministically from the seed.
SolidCheck check_set_operation(const SolidTree& result, const ExactSolid& a, const ExactSolid& b,
                               std::span<const Polygon> a_polys, std::span<const Polygon> b_polys, SetOp op,
                               const SolidCheckSettings& settings);

// The relative tolerance the volume checks use: exact cells sum to the corefinement's volume up to
// the rounding of the plane equations and of the clipping.
inline constexpr double kVolumeRelativeTolerance = 1e-9;

nlohmann::json to_json(const SolidCheck& c);
nlohmann::json to_json(const MergeStats& s);
nlohmann::json to_json(const SolidSize& s);

}  // namespace bsp
