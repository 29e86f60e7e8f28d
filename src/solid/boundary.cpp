#include "solid/boundary.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/errors.h"
#include "solid/cells.h"

namespace bsp {

namespace {

struct Piece {
  Ref at;
  std::uint32_t loop;
};

// Pushes a loop lying in plane `own` down from `root`; returns each final piece with the leaf it
// reached. A node whose plane is `own` itself (or its flip: a cell face lies in the very plane that
// cut it) sends the loop to the side `own` faces; any other node cuts it by the sign of each
// vertex's distance, as the cells were cut. Deciding "coplanar" by a tolerance instead would let a
// face skip a cell thinner than plane_eps on one side and not on the other, and count that part of
// the boundary twice.
void push_down(Ref root, std::span<const Vec3> start, const SolidTree& solid, const Plane& own, LoopPool& pool,
               std::vector<Piece>& reached) {
  pool = {};
  reached.clear();
  std::vector<Piece> stack{{root, pool.add(start)}};
  std::vector<Vec3> front, back;
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    if (is_leaf(p.at)) {
      reached.push_back(p);
      continue;
    }
    const SolidNode& n = solid.nodes[p.at];
    const std::span<const Vec3> loop = pool[p.loop];
    const Side side = n.plane == own || n.plane == own.flipped() ? Side::Coplanar : classify(loop, n.plane, 0.0);
    switch (side) {
      case Side::Front: stack.push_back({n.front, p.loop}); break;
      case Side::Back: stack.push_back({n.back, p.loop}); break;
      case Side::Coplanar: stack.push_back({dot(own.n, n.plane.n) > 0 ? n.front : n.back, p.loop}); break;
      case Side::Spanning:
        split_loop(loop, n.plane, 0.0, front, back);
        stack.push_back({n.front, pool.add(front)});
        stack.push_back({n.back, pool.add(back)});
        break;
    }
  }
}

}  // namespace

LoopPool solid_boundary(const SolidTree& solid) {
  LoopPool out, pieces;
  std::vector<Piece> reached;
  for_each_in_cell(solid, [&](const Cell& cell) {
    for (std::uint32_t i = 0; i < cell.faces.size(); ++i) {
      // The points just outside a face cut by node a lie in a's other child: the face lies in shp(a).
      const Ref a = cell.cut_by[i];
      if (a == kNoNode) {
        out.add(cell.faces[i]);
        continue;
      }
      const Ref beyond = solid.nodes[a].child(dot(cell.outward[i].n, solid.nodes[a].plane.n) > 0);
      push_down(beyond, cell.faces[i], solid, cell.outward[i], pieces, reached);
      for (const Piece& p : reached)
        if (p.at == kOut) out.add(pieces[p.loop]);
    }
  });
  return out;
}

BoundaryCheck check_boundary(const LoopPool& faces, double tol, IndexedMesh* mesh_out) {
  WeldResult w = weld_loops(faces, tol);
  BoundaryCheck c;
  c.dropped_faces = w.dropped_faces;
  c.t_junctions = split_t_junctions(w.mesh, tol);
  c.faces = w.mesh.face_count();
  c.vertices = w.mesh.vertices.size();
  c.edges = edge_report(w.mesh);
  c.volume = enclosed_volume(w.mesh);
  if (mesh_out) *mesh_out = std::move(w.mesh);
  return c;
}

void require_closed_solid(std::span<const Polygon> polys, double tol, std::string_view origin) {
  LoopPool loops;
  std::vector<Vec3> loop;
  for (const Polygon& p : polys) {
    loop.clear();
    for (const Vertex& v : p.verts) loop.push_back(v.p);
    loops.add(loop);
  }
  const BoundaryCheck c = check_boundary(loops, tol);
  const std::string where(origin);
  if (c.edges.border_edges > 0)
    throw InputError(where + ": not a closed solid: " + std::to_string(c.edges.border_edges) + " border edges");
  if (c.edges.repeated_directed > 0)
    throw InputError(where + ": not a consistently oriented solid: " + std::to_string(c.edges.repeated_directed) +
                     " edges used twice in one direction");
  if (!(c.volume > 0))
    throw InputError(where + ": faces point inwards (enclosed volume " + std::to_string(c.volume) + ")");
}

}  // namespace bsp
