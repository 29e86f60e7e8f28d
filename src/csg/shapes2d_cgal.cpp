// OpenSCAD 2021.01's 2D booleans, hulls and triangulation with CGAL (see shapes2d.h).
//
// Notation:
//   grid      integer coordinates X = c * 2^16 (Clipper's, CLIPPER_SCALE in OpenSCAD's clipper-utils.h)
//   IRing     a ring on the grid
//   group     the operands Clipper adds together: 0 = subject (first operand), 1 = clip (the rest)
//   w_g(f)    winding number of group g around the arrangement face f
//   d         a curve's winding contribution per group, counted in its left-to-right direction;
//             crossing halfedge h from its right to its left adds d (h left-to-right) or -d
//   selected  a face inside the result; a boundary halfedge has a selected face on its left and an
//             unselected one on its right, so outer rings run counter-clockwise and holes clockwise
#include "csg/shapes2d.h"

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <list>
#include <map>
#include <tuple>
#include <unordered_set>

namespace bsp::csg {

namespace {

// ---- Clipper's grid ----------------------------------------------------------------------------

struct IPoint {
  std::int64_t x = 0, y = 0;
  bool operator==(const IPoint&) const = default;
};
using IRing = std::vector<IPoint>;

// OpenSCAD's fromOutline2d: c * 2^16 converted to Clipper's integer type, which truncates toward 0.
IRing to_grid(const Ring& r) {
  IRing out;
  out.reserve(r.points.size());
  for (const Vec2& v : r.points)
    out.push_back({static_cast<std::int64_t>(v.x * kClipperScale), static_cast<std::int64_t>(v.y * kClipperScale)});
  return out;
}

std::vector<IRing> to_grid(const Shape2& s) {
  std::vector<IRing> out;
  for (const Ring& r : s.rings) out.push_back(to_grid(r));
  return out;
}

// OpenSCAD's toPolygon2d: X / 2^16 (exact).
Shape2 from_grid(const std::vector<IRing>& rings) {
  Shape2 out;
  for (const IRing& r : rings) {
    Ring ring;
    for (const IPoint& p : r) ring.points.push_back({p.x / kClipperScale, p.y / kClipperScale});
    out.rings.push_back(std::move(ring));
  }
  return out;
}

// Twice the signed area of (a, b, c), exactly (grid coordinates can exceed 2^31).
__int128 cross(const IPoint& a, const IPoint& b, const IPoint& c) {
  return static_cast<__int128>(b.x - a.x) * (c.y - a.y) - static_cast<__int128>(b.y - a.y) * (c.x - a.x);
}

// A ring as a circular doubly linked list, so vertices can be dropped while walking it.
struct Loop {
  explicit Loop(const IRing& r) : pt(r), next(r.size()), prev(r.size()), done(r.size(), false) {
    const std::size_t n = r.size();
    for (std::size_t i = 0; i < n; ++i) {
      next[i] = (i + 1) % n;
      prev[(i + 1) % n] = i;
    }
    size = n;
  }
  // Unlinks i and returns its predecessor, which is then to be examined again.
  std::size_t drop(std::size_t i) {
    const std::size_t p = prev[i];
    next[p] = next[i];
    prev[next[i]] = p;
    done[p] = false;
    --size;
    return p;
  }
  IRing from(std::size_t start) const {
    IRing out;
    for (std::size_t i = 0, k = start; i < size; ++i, k = next[k]) out.push_back(pt[k]);
    return out;
  }
  IRing pt;
  std::vector<std::size_t> next, prev;
  std::vector<bool> done;
  std::size_t size = 0;
};

// Clipper drops repeated and collinear vertices (spikes included) from its results, since OpenSCAD
// leaves PreserveCollinear off. Fewer than 3 left: the ring vanishes.
IRing drop_collinear(const IRing& ring) {
  if (ring.size() < 3) return {};
  Loop l(ring);
  std::size_t cur = 0;
  while (l.size >= 3 && !l.done[cur]) {
    const IPoint &a = l.pt[l.prev[cur]], &b = l.pt[cur], &c = l.pt[l.next[cur]];
    if (a == b || b == c || cross(a, b, c) == 0) {
      cur = l.drop(cur);
    } else {
      l.done[cur] = true;
      cur = l.next[cur];
    }
  }
  return l.size < 3 ? IRing{} : l.from(cur);
}

// Clipper's DistanceFromLineSqrd: squared distance of p from the line through a and b, in doubles.
double distance_sqr(const IPoint& p, const IPoint& a, const IPoint& b) {
  const double A = double(a.y - b.y), B = double(b.x - a.x);
  const double C = A * p.x + B * p.y - (A * a.x + B * a.y);
  return (C * C) / (A * A + B * B);
}

// Clipper's SlopesNearCollinear: whichever of the three points lies between the other two along
// the dominant axis of p1-p2 is tested against the line through the others.
bool near_collinear(const IPoint& p1, const IPoint& p2, const IPoint& p3, double dist_sqr) {
  const bool by_x = std::llabs(p1.x - p2.x) > std::llabs(p1.y - p2.y);
  auto u = [by_x](const IPoint& p) { return by_x ? p.x : p.y; };
  if ((u(p1) > u(p2)) == (u(p1) < u(p3))) return distance_sqr(p1, p2, p3) < dist_sqr;
  if ((u(p2) > u(p1)) == (u(p2) < u(p3))) return distance_sqr(p2, p1, p3) < dist_sqr;
  return distance_sqr(p3, p1, p2) < dist_sqr;
}

bool close(const IPoint& a, const IPoint& b, double dist_sqr) {
  const double dx = double(a.x) - double(b.x), dy = double(a.y) - double(b.y);
  return dx * dx + dy * dy <= dist_sqr;
}

// Clipper's CleanPolygon with its default distance (1.415 units), which OpenSCAD's toPolygon2d
// applies to every result ring: drops a vertex near its predecessor, a vertex whose neighbours are
// near each other (with its successor), or a vertex on a nearly straight run.
IRing clean(const IRing& ring) {
  constexpr double kDistance = 1.415;
  const double d2 = kDistance * kDistance;
  if (ring.empty()) return {};
  Loop l(ring);
  std::size_t cur = 0;
  while (!l.done[cur] && l.next[cur] != l.prev[cur]) {
    const IPoint &a = l.pt[l.prev[cur]], &b = l.pt[cur], &c = l.pt[l.next[cur]];
    if (close(b, a, d2)) {
      cur = l.drop(cur);
    } else if (close(a, c, d2)) {
      l.drop(l.next[cur]);
      cur = l.drop(cur);
    } else if (near_collinear(a, b, c, d2)) {
      cur = l.drop(cur);
    } else {
      l.done[cur] = true;
      cur = l.next[cur];
    }
  }
  return l.size < 3 ? IRing{} : l.from(cur);
}

// ---- exact regions on an arrangement ---------------------------------------------------------

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
struct Wind {
  long d[2] = {0, 0};
  bool operator==(const Wind& o) const { return d[0] == o.d[0] && d[1] == o.d[1]; }
};
// Overlapping pieces of input edges add their contributions.
struct WindMerge {
  Wind operator()(const Wind& a, const Wind& b) const { return {{a.d[0] + b.d[0], a.d[1] + b.d[1]}}; }
};
using SegTraits = CGAL::Arr_segment_traits_2<EK>;
using Traits = CGAL::Arr_curve_data_traits_2<SegTraits, Wind, WindMerge>;
struct FaceWind {
  bool seen = false;
  long w[2] = {0, 0};
};
using Arr = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, FaceWind>>;
using Halfedge = Arr::Halfedge_const_handle;
using Selector = std::function<bool(const long (&w)[2])>;

// The rings of each group as data-carrying segments; a ring's edge from p to q adds +1 to its
// group's winding on its left, which is -1 in the left-to-right direction when p is right of q.
std::vector<Traits::Curve_2> curves(const std::vector<IRing> (&groups)[2]) {
  std::vector<Traits::Curve_2> out;
  for (int g = 0; g < 2; ++g)
    for (const IRing& r : groups[g])
      for (std::size_t i = 0, n = r.size(); i < n; ++i) {
        const IPoint &a = r[i], &b = r[(i + 1) % n];
        if (a == b) continue;
        const EK::Point_2 p(double(a.x), double(a.y)), q(double(b.x), double(b.y));
        Wind w;
        w.d[g] = CGAL::compare_xy(p, q) == CGAL::SMALLER ? 1 : -1;
        out.emplace_back(SegTraits::Curve_2(p, q), w);
      }
  return out;
}

// Change of winding from the right of h to its left.
void add_crossing(const Halfedge& h, int sign, long (&w)[2]) {
  const Wind& d = h->curve().data();
  const int s = (h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? 1 : -1) * sign;
  w[0] += s * d.d[0];
  w[1] += s * d.d[1];
}

// Breadth-first over faces from the unbounded one (winding 0): each neighbour across a halfedge.
void assign_windings(Arr& arr) {
  std::deque<Arr::Face_handle> queue{arr.unbounded_face()};
  arr.unbounded_face()->data().seen = true;
  auto visit_ccb = [&](Arr::Ccb_halfedge_circulator start, const FaceWind& here) {
    auto h = start;
    do {
      Arr::Face_handle other = h->twin()->face();
      if (!other->data().seen) {
        FaceWind fw = here;
        add_crossing(h, -1, fw.w);  // from h's left (here) to its right (other)
        other->set_data(fw);
        queue.push_back(other);
      }
    } while (++h != start);
  };
  while (!queue.empty()) {
    Arr::Face_handle f = queue.front();
    queue.pop_front();
    const FaceWind here = f->data();
    for (auto c = f->outer_ccbs_begin(); c != f->outer_ccbs_end(); ++c) visit_ccb(*c, here);
    for (auto c = f->inner_ccbs_begin(); c != f->inner_ccbs_end(); ++c) visit_ccb(*c, here);
  }
}

// Clipper's Round (ties away from zero) of an exact coordinate, decided exactly.
std::int64_t round_exact(const EK::FT& v) {
  std::int64_t k = std::llround(CGAL::to_double(v));
  const EK::FT half(0.5);
  const bool neg = v < 0;
  for (;;) {
    const EK::FT kk{static_cast<double>(k)};
    if (neg ? !(v <= kk + half) : !(v < kk + half)) ++k;
    else if (neg ? !(v > kk - half) : !(v >= kk - half)) --k;
    else return k;
  }
}

// The boundary of the selected faces as rings: from a boundary halfedge, the next one is the first
// boundary halfedge met turning around its target through selected faces (so rings touching at a
// vertex stay apart). Vertices rounded to the grid, collinear ones dropped.
std::vector<IRing> trace(const Arr& arr, const Selector& selected) {
  auto in = [&](Arr::Face_const_handle f) { return selected(f->data().w); };
  auto boundary = [&](Halfedge h) { return in(h->face()) && !in(h->twin()->face()); };
  std::vector<IRing> out;
  std::unordered_set<const void*> used;
  for (auto e = arr.halfedges_begin(); e != arr.halfedges_end(); ++e) {
    Halfedge start = e;
    if (!boundary(start) || used.count(&*start)) continue;
    IRing ring;
    Halfedge h = start;
    do {
      used.insert(&*h);
      const auto& p = h->source()->point();
      ring.push_back({round_exact(p.x()), round_exact(p.y())});
      Halfedge n = h->next();
      while (!boundary(n)) n = n->twin()->next();
      h = n;
    } while (h != start);
    ring = drop_collinear(ring);
    if (!ring.empty()) out.push_back(std::move(ring));
  }
  return out;
}

// One Clipper Execute: the selected region of the two groups, on the grid, before CleanPolygon.
std::vector<IRing> execute(const std::vector<IRing> (&groups)[2], const Selector& selected) {
  Arr arr;
  const auto cv = curves(groups);
  CGAL::insert(arr, cv.begin(), cv.end());
  assign_windings(arr);
  return trace(arr, selected);
}

// OpenSCAD's toPolygon2d: CleanPolygon on every ring, then back to doubles.
Shape2 finish(const std::vector<IRing>& rings) {
  std::vector<IRing> kept;
  for (const IRing& r : rings) {
    IRing c = clean(r);
    if (c.size() >= 3) kept.push_back(std::move(c));
  }
  return from_grid(kept);
}

// ---- OpenSCAD's tessellation (Polygon2d-CGAL.cc) ---------------------------------------------

struct NestingInfo {
  int nesting_level = 42;
  bool in_domain() const { return nesting_level % 2 == 1; }
};
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
using Fbb = CGAL::Triangulation_face_base_with_info_2<NestingInfo, IK>;
using Fb = CGAL::Constrained_triangulation_face_base_2<IK, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_2<IK>, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<IK, Tds, CGAL::Exact_predicates_tag>;

// Floods the faces reachable from `start` without crossing a constraint with `level`; constrained
// edges to unmarked faces go to `border` for the next level.
void flood(Cdt& cdt, Cdt::Face_handle start, int level, std::deque<Cdt::Edge>& border) {
  if (start->info().nesting_level != -1) return;
  std::deque<Cdt::Face_handle> queue{start};
  while (!queue.empty()) {
    Cdt::Face_handle f = queue.front();
    queue.pop_front();
    if (f->info().nesting_level != -1) continue;
    f->info().nesting_level = level;
    for (int i = 0; i < 3; ++i) {
      Cdt::Face_handle n = f->neighbor(i);
      if (n->info().nesting_level != -1) continue;
      if (cdt.is_constrained(Cdt::Edge(f, i))) border.push_back(Cdt::Edge(f, i));
      else queue.push_back(n);
    }
  }
}

// OpenSCAD's mark_domains: nesting level 0 outside, +1 across each constraint; odd is inside.
void mark_domains(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().nesting_level = -1;
  std::deque<Cdt::Edge> border;
  flood(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting_level == -1) flood(cdt, n, e.first->info().nesting_level + 1, border);
  }
}

}  // namespace

Shape2 boolean2(Op2 op, const std::vector<Shape2>& operands) {
  if (operands.empty()) return {};
  if (operands.size() == 1) return operands[0];  // OpenSCAD copies a lone child, no Clipper
  auto nz = [](long w) { return w != 0; };  // pftNonZero
  if (op == Op2::Intersection) {
    // clipper-utils.cc: a chain of binary intersections, each result fed back as paths.
    std::vector<IRing> source = to_grid(operands[0]);
    for (std::size_t i = 1; i < operands.size(); ++i) {
      const std::vector<IRing> groups[2] = {source, to_grid(operands[i])};
      source = execute(groups, [&](const long (&w)[2]) { return nz(w[0]) && nz(w[1]); });
    }
    return finish(source);
  }
  std::vector<IRing> groups[2] = {to_grid(operands[0]), {}};
  for (std::size_t i = 1; i < operands.size(); ++i)
    for (IRing& r : to_grid(operands[i])) groups[1].push_back(std::move(r));
  if (op == Op2::Union) return finish(execute(groups, [&](const long (&w)[2]) { return nz(w[0]) || nz(w[1]); }));
  return finish(execute(groups, [&](const long (&w)[2]) { return nz(w[0]) && !nz(w[1]); }));
}

Shape2 sanitize2(const Shape2& shape) {
  const std::vector<IRing> groups[2] = {to_grid(shape), {}};
  return finish(execute(groups, [](const long (&w)[2]) { return (w[0] & 1) != 0; }));  // pftEvenOdd
}

Shape2 hull2(const std::vector<Shape2>& shapes) {
  std::vector<IK::Point_2> pts;
  for (const Shape2& s : shapes)
    for (const Ring& r : s.rings)
      for (const Vec2& v : r.points) pts.emplace_back(v.x, v.y);
  std::vector<IK::Point_2> hull;
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  if (hull.size() < 3) return {};
  Ring ring;
  for (const auto& p : hull) ring.points.push_back({p.x(), p.y()});
  return {{ring}};
}

std::vector<Triangle2> triangulate(const Shape2& shape) {
  Cdt cdt;
  // Polygon2d::tessellate: each ring from its last point, every edge a constraint.
  for (const Ring& r : shape.rings) {
    if (r.points.empty()) continue;
    auto prev = cdt.insert({r.points.back().x, r.points.back().y});
    for (const Vec2& v : r.points) {
      auto curr = cdt.insert({v.x, v.y});
      if (prev != curr) {
        cdt.insert_constraint(prev, curr);
        prev = curr;
      }
    }
  }
  mark_domains(cdt);
  std::vector<Triangle2> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->info().in_domain()) continue;
    Triangle2 t;
    for (int i = 0; i < 3; ++i) t[i] = {f->vertex(i)->point().x(), f->vertex(i)->point().y()};
    out.push_back(t);
  }
  return out;
}

Mesh hull3(const std::vector<Vec3>& points) {
  if (points.size() <= 3) return {};
  std::list<IK::Point_3> pts;
  for (const Vec3& p : points) pts.emplace_back(p.x, p.y, p.z);
  // Refuse flat input before CGAL makes a zero-volume polyhedron of it.
  const IK::Point_3& a = pts.front();
  auto b = std::find_if(pts.begin(), pts.end(), [&](const IK::Point_3& p) { return p != a; });
  if (b == pts.end()) return {};
  auto c = std::find_if(pts.begin(), pts.end(), [&](const IK::Point_3& p) { return !CGAL::collinear(a, *b, p); });
  if (c == pts.end()) return {};
  auto d = std::find_if(pts.begin(), pts.end(), [&](const IK::Point_3& p) { return !CGAL::coplanar(a, *b, *c, p); });
  if (d == pts.end()) return {};
  CGAL::Polyhedron_3<IK> poly;
  CGAL::convex_hull_3(pts.begin(), pts.end(), poly);
  // createPolySetFromPolyhedron: facets in order, each facet's vertices around its halfedges;
  // points numbered by first use as OpenSCAD's OFF export does (here, not with openscad_shapes.h's
  // indexed(), so that this CGAL library needs nothing from the library that links it).
  Mesh out;
  std::map<std::tuple<double, double, double>, std::uint32_t> index;
  for (auto f = poly.facets_begin(); f != poly.facets_end(); ++f) {
    std::vector<std::uint32_t> face;
    auto h = f->facet_begin(), end = h;
    do {
      const auto& p = h->vertex()->point();
      auto [it, fresh] = index.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(out.points.size()));
      if (fresh) out.points.push_back({p.x(), p.y(), p.z()});
      face.push_back(it->second);
    } while (++h != end);
    out.faces.push_back(std::move(face));
  }
  return out;
}

}  // namespace bsp::csg
