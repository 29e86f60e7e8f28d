#include "solid/cells.h"

#include <algorithm>
#include <cmath>

#include "geometry/polygon.h"
#include "geometry/polytope.h"

namespace bsp {

Cell box_cell(const Box& box) {
  Cell cell;
  const ConvexPolytope p = ConvexPolytope::box(box);
  for (std::size_t f = 0; f < p.face_count(); ++f) {
    cell.faces.add(p.face(f));
    cell.outward.push_back(Plane::through(newell_normal(p.face(f)), p.face(f).front()));
    cell.cut_by.push_back(kNoNode);
  }
  return cell;
}

namespace {

bool lex_less(const Vec3& a, const Vec3& b) {
  return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}

// The cap's directed edges: for each face crossing the plane, the chord from where its loop enters
// the back side (X) to where it leaves (Y); for each face touching the plane along an edge p->q,
// that edge reversed (q->p) on the side the face lies. Cut points are bit-identical from both
// faces of an edge (edge_cut), so the chords chain exactly into the cap. `consistent` is false when
// rounding made a face's signs non-convex (more than one crossing each way, or an edge on the plane
// of a crossing face).
struct CapEdges {
  std::vector<std::pair<Vec3, Vec3>> back, front;  // each oriented counter-clockwise seen from outside its cell
  bool consistent = true;
};

// `d` is scratch for the vertices' distances, reused across faces.
void face_cap_edges(std::span<const Vec3> loop, const Plane& plane, std::vector<double>& d, CapEdges& out) {
  const std::size_t m = loop.size();
  d.resize(m);
  bool any_front = false, any_back = false;
  for (std::size_t k = 0; k < m; ++k) {
    d[k] = plane.distance(loop[k]);
    any_front |= d[k] > 0;
    any_back |= d[k] < 0;
  }
  int entries = 0, exits = 0;
  Vec3 x, y;
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t prev = k == 0 ? m - 1 : k - 1, next = k + 1 == m ? 0 : k + 1;
    const double dp = d[k], dq = d[next];
    if (dp == 0 && dq == 0) {
      if (any_front && any_back) out.consistent = false;
      else (any_back ? out.back : out.front).push_back({loop[next], loop[k]});
      continue;
    }
    if (dp > 0 && dq < 0) x = edge_cut(loop[k], loop[next], dp, dq), ++entries;
    if (dp < 0 && dq > 0) y = edge_cut(loop[k], loop[next], dp, dq), ++exits;
    if (dp == 0 && d[prev] > 0 && dq < 0) x = loop[k], ++entries;
    if (dp == 0 && d[prev] < 0 && dq > 0) y = loop[k], ++exits;
  }
  if (!(any_front && any_back)) return;
  if (entries != 1 || exits != 1) {
    out.consistent = false;
    return;
  }
  if (x == y) return;  // a chord of no length
  out.back.push_back({x, y});
  out.front.push_back({y, x});
}

// The cap as one loop, following each edge's end to the edge starting there; empty when the edges
// do not form exactly one closed loop.
std::vector<Vec3> chain(std::vector<std::pair<Vec3, Vec3>> edges) {
  const auto by_start = [](const auto& a, const auto& b) { return lex_less(a.first, b.first); };
  std::sort(edges.begin(), edges.end(), by_start);
  for (std::size_t i = 1; i < edges.size(); ++i)
    if (edges[i].first == edges[i - 1].first) return {};
  std::vector<Vec3> loop;
  if (edges.size() < 3) return loop;
  Vec3 p = edges.front().first;
  for (std::size_t steps = 0; steps < edges.size(); ++steps) {
    loop.push_back(p);
    const auto it = std::lower_bound(edges.begin(), edges.end(), std::pair{p, p}, by_start);
    if (it == edges.end() || it->first != p) return {};
    p = it->second;
    if (p == loop.front()) return steps + 1 == edges.size() ? loop : std::vector<Vec3>{};
  }
  return {};
}

// Fallback when the chords do not chain (signs made non-convex by rounding): every cut point, once,
// ordered by angle about their centroid.
std::vector<Vec3> by_angle(std::vector<Vec3> cut, const Vec3& n) {
  std::sort(cut.begin(), cut.end(), lex_less);
  cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
  if (cut.size() < 3) return {};
  Vec3 c;
  for (const Vec3& p : cut) c += p;
  c = c / static_cast<double>(cut.size());
  const Vec3 u = normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
  const Vec3 v = cross(n, u);
  std::vector<std::pair<double, Vec3>> sorted;
  for (const Vec3& p : cut) sorted.push_back({std::atan2(dot(p - c, v), dot(p - c, u)), p});
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  cut.clear();
  for (const auto& a : sorted) cut.push_back(a.second);
  return cut;
}

void add_cap(Cell& cell, const std::vector<Vec3>& cap, const Plane& outward, Ref node) {
  if (cap.size() < 3) return;
  cell.faces.add(cap);
  cell.outward.push_back(outward);
  cell.cut_by.push_back(node);
}

// Every point where the plane meets an edge of the cell (for the fallback).
std::vector<Vec3> cut_points(const Cell& cell, const Plane& plane) {
  std::vector<Vec3> cut;
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) {
    const std::span<const Vec3> loop = cell.faces[i];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3& p = loop[k];
      const Vec3& q = loop[k + 1 == loop.size() ? 0 : k + 1];
      const double dp = plane.distance(p), dq = plane.distance(q);
      if (dp == 0) cut.push_back(p);
      if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) cut.push_back(edge_cut(p, q, dp, dq));
    }
  }
  return cut;
}

}  // namespace

void split_cell(const Cell& cell, const Plane& plane, Ref node, Cell& front, Cell& back) {
  front = {};
  back = {};
  bool any_front = false, any_back = false;
  for (const Vec3& p : cell.faces.points) {
    const double d = plane.distance(p);
    any_front |= d > 0;
    any_back |= d < 0;
  }
  if (!any_back || !any_front) {
    (any_back ? back : front) = cell;
    return;
  }
  std::vector<Vec3> f, b;
  std::vector<double> distances;
  CapEdges edges;
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) {
    const std::span<const Vec3> loop = cell.faces[i];
    split_loop(loop, plane, 0.0, f, b);
    if (!f.empty()) front.faces.add(f), front.outward.push_back(cell.outward[i]), front.cut_by.push_back(cell.cut_by[i]);
    if (!b.empty()) back.faces.add(b), back.outward.push_back(cell.outward[i]), back.cut_by.push_back(cell.cut_by[i]);
    face_cap_edges(loop, plane, distances, edges);
  }
  std::vector<Vec3> back_cap = edges.consistent ? chain(edges.back) : std::vector<Vec3>{};
  std::vector<Vec3> front_cap = edges.consistent ? chain(edges.front) : std::vector<Vec3>{};
  if (back_cap.empty() || front_cap.empty()) {
    const std::vector<Vec3> cut = cut_points(cell, plane);
    back_cap = by_angle(cut, plane.n);
    front_cap = by_angle(cut, -plane.n);
  }
  add_cap(front, front_cap, plane.flipped(), node);
  add_cap(back, back_cap, plane, node);
}

double cell_volume(const Cell& cell) {
  double v = 0;
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) v += dot(newell_normal(cell.faces[i]), cell.faces[i].front());
  return v / 6.0;
}

double solid_volume(const SolidTree& solid) {
  double volume = 0;
  for_each_in_cell(solid, [&](const Cell& cell) { volume += cell_volume(cell); });
  return volume;
}

}  // namespace bsp
