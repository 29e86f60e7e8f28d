#pragma once
// Polygon soups as indexed meshes: welding coincident vertices, splitting edges at the vertices
// that lie on them (T-junctions), and the edge counts that say whether a surface is closed.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/convex_loop.h"
#include "geometry/vec3.h"

namespace bsp {

struct IndexedMesh {
  std::vector<Vec3> vertices;
  std::vector<std::uint32_t> corners;  // face f is corners[start[f], start[f + 1])
  std::vector<std::uint32_t> start = std::vector<std::uint32_t>(1, 0);
  std::size_t face_count() const { return start.size() - 1; }
};

// Corners within tol of each other become one vertex, transitively (a chain of corners each within
// tol of the next is one vertex, placed at its first corner, so the result is deterministic); a
// face that repeats a vertex in a row keeps it once, and a face left with fewer than 3 corners is
// dropped and counted.
struct WeldResult {
  IndexedMesh mesh;
  std::uint64_t dropped_faces = 0;
};
WeldResult weld_loops(const LoopPool& loops, double tol);

// Inserts into every edge the vertices lying on it (within tol of the segment, strictly between its
// ends), in order along the edge. Returns how many were inserted. After this, two faces that share
// a stretch of boundary share its edges.
std::uint64_t split_t_junctions(IndexedMesh& mesh, double tol);

// A closed, consistently oriented surface uses every edge once in each direction.
struct EdgeReport {
  std::uint64_t edges = 0;             // undirected
  std::uint64_t border_edges = 0;      // used more often in one direction than in the other
  // Directed edges used by more than one face: inconsistent facing, or a non-manifold edge (where
  // two parts of a closed surface touch along a curve, as in a symmetric difference).
  std::uint64_t repeated_directed = 0;
  bool closed() const { return border_edges == 0; }
  bool manifold() const { return repeated_directed == 0; }
};
EdgeReport edge_report(const IndexedMesh& mesh);

// The signed volume the faces enclose (divergence theorem): positive when they face outwards.
double enclosed_volume(const IndexedMesh& mesh);

}  // namespace bsp
