#include "solid/boundary.h"

#include <algorithm>
#include <string>
#include <vector>

#include "common/errors.h"

namespace bsp {

namespace {

struct Piece {
  Ref at;
  std::uint32_t loop;
};

// Pushes the loops of `start` down from `root`; returns each final piece with the leaf it reached.
// `off` is the direction from the pieces to the points whose labels are wanted.
void push_down(Ref root, const LoopPool& start, const SolidTree& solid, const Vec3& off, LoopPool& pool,
               std::vector<Piece>& reached) {
  pool = start;
  reached.clear();
  std::vector<Piece> stack;
  for (std::uint32_t i = 0; i < start.size(); ++i) stack.push_back({root, i});
  std::vector<Vec3> front, back;
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    if (is_leaf(p.at)) {
      reached.push_back(p);
      continue;
    }
    const SolidNode& n = solid.nodes[p.at];
    switch (classify(pool[p.loop], n.plane, solid.tol.plane_eps)) {
      case Side::Front: stack.push_back({n.front, p.loop}); break;
      case Side::Back: stack.push_back({n.back, p.loop}); break;
      case Side::Coplanar: stack.push_back({dot(off, n.plane.n) > 0 ? n.front : n.back, p.loop}); break;
      case Side::Spanning:
        split_loop(pool[p.loop], n.plane, solid.tol.plane_eps, front, back);
        stack.push_back({n.front, pool.add(front)});
        stack.push_back({n.back, pool.add(back)});
        break;
    }
  }
}

}  // namespace

LoopPool solid_boundary(const SolidTree& solid) {
  LoopPool out;
  LoopPool one, in_front, pieces;
  std::vector<Piece> front_reached, back_reached;
  std::vector<Vec3> reversed;
  for (std::size_t v = 0; v < solid.nodes.size(); ++v) {
    const std::span<const Vec3> shp = solid.loops[solid.shp[v]];
    if (shp.empty()) continue;
    const SolidNode& n = solid.nodes[v];
    one = {};
    one.add(shp);
    push_down(n.front, one, solid, n.plane.n, in_front, front_reached);
    for (const Piece& f : front_reached) {
      one = {};
      one.add(in_front[f.loop]);
      push_down(n.back, one, solid, -n.plane.n, pieces, back_reached);
      for (const Piece& b : back_reached) {
        if (b.at == f.at) continue;
        const std::span<const Vec3> loop = pieces[b.loop];
        if (f.at == kOut) {
          out.add(loop);
        } else {
          reversed.assign(loop.rbegin(), loop.rend());
          out.add(reversed);
        }
      }
    }
  }
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
