#include "geometry/polytope.h"

#include <algorithm>
#include <cmath>

namespace bsp {

namespace {

Polygon quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {{{a, 0, 0}, {b, 0, 0}, {c, 0, 0}, {d, 0, 0}}, 0};
}

// Orders points lying on `plane` into a convex polygon whose Newell normal points along `outward`.
// Points closer than eps to an earlier one are merged.
Polygon cap_polygon(std::vector<Vec3> pts, const Vec3& outward, double eps) {
  std::vector<Vec3> unique;
  for (const auto& p : pts)
    if (std::none_of(unique.begin(), unique.end(), [&](const Vec3& q) { return length(p - q) <= eps; }))
      unique.push_back(p);
  Polygon cap;
  if (unique.size() < 3) return cap;
  Vec3 c;
  for (const auto& p : unique) c += p;
  c = c / static_cast<double>(unique.size());
  const Vec3 u = normalize(std::abs(outward.x) < 0.9 ? cross(outward, Vec3{1, 0, 0}) : cross(outward, Vec3{0, 1, 0}));
  const Vec3 v = cross(outward, u);
  // Counter-clockwise about `outward` in the (u, v) basis.
  std::sort(unique.begin(), unique.end(), [&](const Vec3& a, const Vec3& b) {
    return std::atan2(dot(a - c, v), dot(a - c, u)) < std::atan2(dot(b - c, v), dot(b - c, u));
  });
  for (const auto& p : unique) cap.verts.push_back({p, 0, 0});
  return cap;
}

}  // namespace

ConvexPolytope ConvexPolytope::box(const Box& b) {
  const Vec3 l = b.lo, h = b.hi;
  ConvexPolytope p;
  p.faces_ = {
      quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, l.y, l.z}),  // z = lo, normal -z
      quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}),  // z = hi, normal +z
      quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}),  // y = lo, normal -y
      quad({l.x, h.y, l.z}, {l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z}),  // y = hi, normal +y
      quad({l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z}),  // x = lo, normal -x
      quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z}),  // x = hi, normal +x
  };
  return p;
}

ConvexPolytope ConvexPolytope::clipped(const Plane& keep, double eps) const {
  bool any_front = false, any_back = false;
  for (const auto& f : faces_)
    for (const auto& v : f.verts) {
      const double d = keep.distance(v.p);
      any_front |= d > eps;
      any_back |= d < -eps;
    }
  if (!any_back) return *this;
  if (!any_front) return {};
  ConvexPolytope out;
  std::vector<Vec3> on_plane;
  for (const auto& f : faces_) {
    const Side side = classify(f, keep, eps);
    if (side == Side::Back) continue;
    Polygon kept = f;
    if (side == Side::Spanning) {
      // Polytope faces are never dropped as slivers: a thin face still bounds the volume.
      SplitResult r = split(f, keep, 0.0);
      if (!r.front) continue;
      kept = std::move(*r.front);
    }
    for (const auto& v : kept.verts)
      if (std::abs(keep.distance(v.p)) <= eps) on_plane.push_back(v.p);
    out.faces_.push_back(std::move(kept));
  }
  Polygon cap = cap_polygon(std::move(on_plane), -keep.n, eps);
  if (!cap.verts.empty()) out.faces_.push_back(std::move(cap));
  return out;
}

namespace {

// Newell's normal (twice the vector area) of a polygon fed one vertex at a time, and one of its
// points, relative to an origin `o`.
struct NewellSum {
  Vec3 o, first, prev, sum, point;
  int count = 0;

  void add(const Vec3& p) {
    const Vec3 q = p - o;
    if (count++ == 0) {
      first = point = q;
    } else {
      sum += cross(prev, q);
    }
    prev = q;
  }
  Vec3 closed() const { return count > 2 ? sum + cross(prev, first) : Vec3{}; }
};

}  // namespace

// Per face, the parts in front of and behind the plane (Sutherland–Hodgman on its vertex loop)
// give their Newell normals N. With the origin on the plane, the cut face adds nothing to
// sum(N · point) / 6, the volume; and a closed surface's normals sum to zero, so the cut face's
// is minus the sum over the other faces of that side.
// A face lying on the plane (every vertex within eps) is left to the cut face: it bounds the side its
// outward normal points away from, where the closure counts it, and touches the other only along
// its edges. When no vertex lies beyond eps on one side, that side is empty, as in clipped().
ConvexPolytope::SplitMeasure ConvexPolytope::measure_split(const Plane& plane, double eps) const {
  // Each vertex's distance, snapped to 0 within eps, computed once: faces_ in order, vertex by vertex.
  thread_local std::vector<double> dist;
  dist.clear();
  bool any_front = false, any_back = false;
  for (const auto& f : faces_)
    for (const auto& v : f.verts) {
      double d = plane.distance(v.p);
      if (std::abs(d) <= eps) d = 0;
      any_front |= d > 0;
      any_back |= d < 0;
      dist.push_back(d);
    }
  if (!any_back) return {volume(), 0.0, surface_area(), 0.0};
  if (!any_front) return {0.0, volume(), 0.0, surface_area()};
  const Vec3 o = plane.n * -plane.d;
  Vec3 front_total, back_total;
  SplitMeasure m;
  const double* d = dist.data();
  for (const auto& f : faces_) {
    const std::size_t k = f.verts.size();
    const double* fd = d;
    d += k;
    if (std::all_of(fd, fd + k, [](double x) { return x == 0; })) continue;
    NewellSum front{o, {}, {}, {}, {}}, back{o, {}, {}, {}, {}};
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t j = i + 1 == k ? 0 : i + 1;
      const Vec3& a = f.verts[i].p;
      const double da = fd[i], db = fd[j];
      if (da >= 0) front.add(a);
      if (da <= 0) back.add(a);
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
        const Vec3 x = a + (f.verts[j].p - a) * (da / (da - db));
        front.add(x);
        back.add(x);
      }
    }
    const Vec3 nf = front.closed(), nb = back.closed();
    front_total += nf;
    back_total += nb;
    m.front_volume += dot(nf, front.point) / 6.0;
    m.back_volume += dot(nb, back.point) / 6.0;
    m.front_area += 0.5 * length(nf);
    m.back_area += 0.5 * length(nb);
  }
  m.front_area += 0.5 * length(front_total);
  m.back_area += 0.5 * length(back_total);
  return m;
}

double ConvexPolytope::volume() const {
  double v = 0;
  for (const auto& f : faces_) v += dot(newell_normal(f), f.verts.front().p);
  return v / 6.0;
}

double ConvexPolytope::surface_area() const {
  double a = 0;
  for (const auto& f : faces_) a += area(f);
  return a;
}

Box ConvexPolytope::bounds() const {
  Box b;
  for (const auto& f : faces_)
    for (const auto& v : f.verts) b.add(v.p);
  return b;
}

}  // namespace bsp
