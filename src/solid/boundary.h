#pragma once
// The boundary of a solid tree [Thibault1987]: the parts of the sub-hyperplanes with an IN cell
// on one side and an OUT cell on the other, and the checks that it bounds a solid.
#include <cstdint>
#include <span>
#include <string_view>

#include "geometry/convex_loop.h"
#include "geometry/mesh_weld.h"
#include "geometry/polygon.h"
#include "solid/solid_tree.h"

namespace bsp {

// Every face of every IN cell (cells.h) is pushed down the subtree beyond the node that cut it,
// where the points just outside it lie: the pieces that reach OUT cells are boundary, facing out.
// (A face of the box bounds the solid where an IN cell touches the box.) A piece lying in a
// node's plane goes to the side those points lie on; any other node cuts it by the sign of each
// vertex's distance, as the cells are cut. So the boundary is the IN cells' own
// faces, and encloses exactly their volume.
LoopPool solid_boundary(const SolidTree& solid);

// The boundary welded (vertices within plane_eps are one), its T-junctions split, and its edges
// counted: what "closed" means for a result.
struct BoundaryCheck {
  std::uint64_t faces = 0, vertices = 0, t_junctions = 0, dropped_faces = 0;
  EdgeReport edges;
  double volume = 0;  // enclosed by the welded faces
};
BoundaryCheck check_boundary(const LoopPool& faces, double tol, IndexedMesh* mesh_out = nullptr);

// Input that claims to bound a solid: throws InputError "ORIGIN: ..." naming the count of border
// edges, of edges used twice in one direction, or an inward facing surface (negative volume).
// Vertices are welded within tol first.
void require_closed_solid(std::span<const Polygon> polys, double tol, std::string_view origin);

}  // namespace bsp
