#pragma once
// Proof of an evaluated program of set operations (solid/set_program.h), as solid_check.h proves
// one operation: points classified by the result tree against the truth the program itself gives
// (CGAL's exact side-of-mesh on every leaf, combined step by step), the result's volume against
// CGAL's corefinement of the same leaves with exact constructions (exact_corefine_program, each
// step's operands combined as a balanced tree), and the boundary closed. A hull of set operations
// (a hull of leaves is a leaf already, csg/lower.h) is taken as the evaluation built it (`hulls`,
// one mesh per hull step in order) by the truth and the volume alike, as leaves are: its vertices
// are the result's, rounded, which CGAL's exact hull of the exact result would not reproduce. Where
// corefinement refuses an intermediate result (not a manifold mesh), the reference volume is CGAL's
// Nef polyhedra's (exact_nef_program).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "geometry/plane_polygon.h"
#include "geometry/polygon.h"
#include "solid/exact_solid_tree.h"
#include "solid/set_program.h"
#include "solid/solid_tree.h"
#include "validate/solid_check.h"

namespace bsp {

struct ProgramCheck {
  bool exact = false;                    // which kernel's result
  std::uint64_t points = 0;
  std::uint64_t on_operand = 0;          // exactly on a leaf's surface: no side to compare
  std::uint64_t within_eps = 0;          // float: within plane_eps of a leaf's surface, counted apart
  std::uint64_t within_eps_disagree = 0;
  std::uint64_t compared = 0;
  std::uint64_t mismatches = 0;
  double volume = 0;                     // the result's, scene units
  double corefine_volume = 0;            // the reference's, scene units (rounded)
  std::string reference;                 // "corefine", or "nef" where corefinement refused a step
  std::string corefine_refused;          // why corefinement refused (then Nef polyhedra gave the volume)
  double volume_relative_error = 0;
  std::string volume_exact, corefine_volume_exact;  // exact kernel: both in grid units, canonical text
  double corefine_seconds = 0;
  std::uint64_t corefine_operations = 0;
  std::string corefine_error;
  std::uint64_t boundary_faces = 0;
  std::uint64_t border_edges = 0;        // float: welded edges used unequally; exact: border segments
  bool volume_ok() const {
    return corefine_error.empty() && (exact ? volume_exact == corefine_volume_exact : volume_relative_error <= kVolumeRelativeTolerance);
  }
  bool ok() const { return mismatches == 0 && border_edges == 0 && volume_ok(); }
};

// Float kernel: `leaves` in scene units, `boundary` the result's (solid_boundary).
ProgramCheck check_program(const SolidTree& result, const LoopPool& boundary, std::span<const std::vector<Polygon>> leaves,
                           std::span<const std::vector<Polygon>> hulls, std::span<const Step> steps,
                           const SolidCheckSettings& settings);

// Exact kernel: `leaves` and `hulls` in scene units (snapped to the space's grid here), `boundary`
// exact_solid_boundary(result); grid points are classified, volumes compared exactly.
ProgramCheck check_exact_program(const ExactSolidTree& result, const ExactSolidSpace& space,
                                 std::span<const PlanePolygon> boundary, std::span<const std::vector<Polygon>> leaves,
                                 std::span<const std::vector<Polygon>> hulls, std::span<const Step> steps,
                                 const SolidCheckSettings& settings);

nlohmann::json to_json(const ProgramCheck& c);

}  // namespace bsp
