#include "geometry/mesh_weld.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/point_grid.h"
#include "geometry/polygon.h"

namespace bsp {

WeldResult weld_loops(const LoopPool& loops, double tol) {
  // Union-find over all corners: two corners within tol are one vertex, and so, transitively, is
  // every chain of them. A greedy first-come weld is not transitive (a within tol of b, b of c, but
  // not a of c) and leaves the two faces around such a chain with edges that do not match.
  const std::vector<Vec3>& pts = loops.points;
  std::vector<std::uint32_t> parent(pts.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  PointGrid grid(std::max(tol, 1e-300));
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    grid.around(pts[i], [&](std::uint32_t j) {
      if (length(pts[j] - pts[i]) > tol) return;
      const std::uint32_t a = find(i), b = find(j);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smallest index represents
    });
    grid.insert(pts[i], i);
  }
  WeldResult r;
  IndexedMesh& m = r.mesh;
  std::vector<std::uint32_t> vertex_of(pts.size(), UINT32_MAX);
  std::vector<std::uint32_t> face;
  for (std::uint32_t f = 0; f < loops.size(); ++f) {
    face.clear();
    for (std::uint32_t c = loops.start[f]; c < loops.start[f + 1]; ++c) {
      const std::uint32_t root = find(c);
      if (vertex_of[root] == UINT32_MAX) {
        vertex_of[root] = static_cast<std::uint32_t>(m.vertices.size());
        m.vertices.push_back(pts[root]);
      }
      const std::uint32_t v = vertex_of[root];
      if (face.empty() || face.back() != v) face.push_back(v);
    }
    while (face.size() > 1 && face.back() == face.front()) face.pop_back();
    if (face.size() < 3) {
      ++r.dropped_faces;
      continue;
    }
    m.corners.insert(m.corners.end(), face.begin(), face.end());
    m.start.push_back(static_cast<std::uint32_t>(m.corners.size()));
  }
  return r;
}

std::uint64_t split_t_junctions(IndexedMesh& mesh, double tol) {
  double total = 0;
  std::uint64_t n_edges = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (std::uint32_t i = mesh.start[f]; i < mesh.start[f + 1]; ++i) {
      const std::uint32_t j = i + 1 == mesh.start[f + 1] ? mesh.start[f] : i + 1;
      total += length(mesh.vertices[mesh.corners[j]] - mesh.vertices[mesh.corners[i]]);
      ++n_edges;
    }
  if (n_edges == 0) return 0;
  // Cells about the mean edge length: an edge is walked in half-cell steps, each looking at the
  // 27 cells around it, so every vertex within tol (< a cell) of the segment is seen.
  PointGrid grid(std::max(total / static_cast<double>(n_edges), 4 * tol));
  for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) grid.insert(mesh.vertices[v], v);
  std::uint64_t inserted = 0;
  IndexedMesh out;
  out.vertices = mesh.vertices;
  std::vector<std::pair<double, std::uint32_t>> on_edge;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (std::uint32_t i = mesh.start[f]; i < mesh.start[f + 1]; ++i) {
      const std::uint32_t j = i + 1 == mesh.start[f + 1] ? mesh.start[f] : i + 1;
      const std::uint32_t ia = mesh.corners[i], ib = mesh.corners[j];
      const Vec3 a = mesh.vertices[ia], ab = mesh.vertices[ib] - a;
      const double len2 = dot(ab, ab);
      out.corners.push_back(ia);
      if (len2 == 0) continue;
      on_edge.clear();
      const auto consider = [&](std::uint32_t v) {
        if (v == ia || v == ib) return;
        const double t = dot(mesh.vertices[v] - a, ab) / len2;
        if (t <= 0 || t >= 1) return;
        if (length(mesh.vertices[v] - (a + ab * t)) <= tol) on_edge.push_back({t, v});
      };
      // Every vertex within tol of the edge is in the cells its box (grown by 2 tol, so that a
      // distance rounded below tol is inside too) meets, and in the 27 cells around some half-cell
      // step along it: the box where it meets fewer cells than the steps would look at (a short or
      // axis-parallel edge), else the steps. Either finds the same vertices, which sorting puts in
      // one order.
      const auto steps = static_cast<std::size_t>(std::ceil(std::sqrt(len2) / (0.5 * grid.cell()))) + 1;
      const Vec3 b = mesh.vertices[ib], margin{2 * tol, 2 * tol, 2 * tol};
      if (!grid.in_box(min(a, b) - margin, max(a, b) + margin, 27 * (steps + 1), consider))
        for (std::size_t s = 0; s <= steps; ++s)
          grid.around(a + ab * (static_cast<double>(s) / static_cast<double>(steps)), consider);
      std::sort(on_edge.begin(), on_edge.end());
      on_edge.erase(std::unique(on_edge.begin(), on_edge.end()), on_edge.end());
      for (const auto& e : on_edge) out.corners.push_back(e.second);
      inserted += on_edge.size();
    }
    out.start.push_back(static_cast<std::uint32_t>(out.corners.size()));
  }
  mesh = std::move(out);
  return inserted;
}

EdgeReport edge_report(const IndexedMesh& mesh) {
  // Every directed edge as (from, to), sorted: equal directed edges are adjacent, and so are the
  // two directions of an undirected edge once each is keyed by its ends in order. Sorting flat
  // keys, not hashing them into node-based maps, keeps a 10^5-face result's report in milliseconds.
  std::vector<std::uint64_t> directed;
  directed.reserve(mesh.corners.size());
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (std::uint32_t i = mesh.start[f]; i < mesh.start[f + 1]; ++i) {
      const std::uint32_t j = i + 1 == mesh.start[f + 1] ? mesh.start[f] : i + 1;
      directed.push_back((std::uint64_t{mesh.corners[i]} << 32) | mesh.corners[j]);
    }
  std::sort(directed.begin(), directed.end());
  EdgeReport r;
  for (std::size_t i = 1; i < directed.size(); ++i)
    r.repeated_directed += directed[i] == directed[i - 1] && (i < 2 || directed[i - 2] != directed[i]);
  // Undirected: (lo, hi) with +1 for lo -> hi and -1 for hi -> lo; a border edge's uses do not cancel.
  std::vector<std::pair<std::uint64_t, int>> undirected;
  undirected.reserve(directed.size());
  for (const std::uint64_t e : directed) {
    const std::uint64_t a = e >> 32, b = e & 0xffffffffu;
    undirected.push_back({(std::min(a, b) << 32) | std::max(a, b), a < b ? 1 : -1});
  }
  std::sort(undirected.begin(), undirected.end());
  for (std::size_t i = 0; i < undirected.size();) {
    std::int64_t balance = 0;
    std::size_t k = i;
    for (; k < undirected.size() && undirected[k].first == undirected[i].first; ++k) balance += undirected[k].second;
    ++r.edges;
    r.border_edges += balance != 0;
    i = k;
  }
  return r;
}

double enclosed_volume(const IndexedMesh& mesh) {
  double v = 0;
  std::vector<Vec3> face;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    face.clear();
    for (std::uint32_t i = mesh.start[f]; i < mesh.start[f + 1]; ++i) face.push_back(mesh.vertices[mesh.corners[i]]);
    v += dot(newell_normal(face), face.front());
  }
  return v / 6.0;
}

}  // namespace bsp
