#pragma once
// Proof of an exact set operation (solid/exact_merge.h) against CGAL on the same snapped operands,
// everything in grid coordinates (which doubles hold exactly), so that nothing is compared within a
// tolerance: grid points classified by the tree against CGAL's exact side-of-mesh predicates on each
// operand, combined by the operation; the boundary's volume, an exact rational, against the volume
// of CGAL's corefinement with exact constructions (Epeck); and the boundary closed, decided
// exactly (validate/exact_measure.h).
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "geometry/plane_polygon.h"
#include "geometry/polygon.h"
#include "solid/exact_solid_tree.h"
#include "solid/merge.h"
#include "validate/exact_measure.h"
#include "validate/solid_check.h"

namespace bsp {

struct ExactSolidCheck {
  std::uint64_t points = 0;
  std::uint64_t on_operand = 0;  // exactly on an operand's surface: no side to compare
  std::uint64_t compared = 0;
  std::uint64_t mismatches = 0;  // of the compared: the tree says otherwise (On included)
  ExactBoundaryCheck boundary;   // the result's boundary: closure and volume, exact, in grid units
  double volume = 0;             // the boundary's volume in scene units (rounded)
  std::string corefine_volume;   // CGAL's, exact, in grid units (canonical text; empty on error)
  double corefine_volume_scene = 0;  // the same rounded, in scene units
  double corefine_seconds = 0;
  std::string corefine_error;    // why CGAL gave no volume (then the volume check fails)
  bool volume_equal() const { return corefine_error.empty() && boundary.volume == corefine_volume; }
  bool ok() const { return mismatches == 0 && boundary.closed() && volume_equal(); }
};

// Throws InputError "NAME: problem" when the polygons, snapped to `grid`, are not a closed solid or
// their faces intersect: what the exact kernel's solids require beyond the float checks. Snapped, a
// closed mesh stays closed (equal vertices snap alike) unless a face collapsed; its faces may come
// to meet, which only exact predicates on the snapped mesh can tell.
void require_snapped_solid(std::span<const Polygon> polys, const Grid& grid, const std::string& name);

// The operands' snapped polygons in grid units, as CGAL is given them.
std::vector<Polygon> grid_unit_polygons(std::span<const Polygon> polys, const Grid& grid);

// The result must be a op b; `boundary` is exact_solid_boundary(result). Grid points are drawn
// deterministically from settings.seed: half uniform in the operands' box, half within
// settings.near_distance of the box's diagonal of a random face.
ExactSolidCheck check_exact_set_operation(const ExactSolidTree& result, const ExactSolidSpace& space,
                                          std::span<const PlanePolygon> boundary, std::span<const Polygon> a,
                                          std::span<const Polygon> b, SetOp op, const SolidCheckSettings& settings);

nlohmann::json to_json(const ExactSolidCheck& c);

}  // namespace bsp
