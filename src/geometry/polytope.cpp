#include "geometry/polytope.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace bsp {

namespace {

// clip_into's scratch, reused across calls on a thread: the face being cut and its front part, the
// cut face's points, and cap_polygon's arrays.
struct ClipScratch {
  Polygon whole, front;
  std::vector<Vec3> on_plane, unique;
  std::vector<std::pair<double, std::uint32_t>> angle;
};

// Orders points lying on `plane` into a convex polygon whose Newell normal points along `outward`,
// appended to `out`. Points closer than eps to an earlier one are merged. Appends nothing and
// returns false when fewer than 3 remain.
bool cap_polygon(const std::vector<Vec3>& pts, const Vec3& outward, double eps, ClipScratch& scratch,
                 std::vector<Vec3>& out) {
  std::vector<Vec3>& unique = scratch.unique;
  unique.clear();
  for (const auto& p : pts)
    if (std::none_of(unique.begin(), unique.end(), [&](const Vec3& q) { return length(p - q) <= eps; }))
      unique.push_back(p);
  if (unique.size() < 3) return false;
  Vec3 c;
  for (const auto& p : unique) c += p;
  c = c / static_cast<double>(unique.size());
  const Vec3 u = normalize(std::abs(outward.x) < 0.9 ? cross(outward, Vec3{1, 0, 0}) : cross(outward, Vec3{0, 1, 0}));
  const Vec3 v = cross(outward, u);
  // Counter-clockwise about `outward` in the (u, v) basis; each angle computed once.
  auto& angle = scratch.angle;
  angle.resize(unique.size());
  for (std::uint32_t i = 0; i < unique.size(); ++i) angle[i] = {std::atan2(dot(unique[i] - c, v), dot(unique[i] - c, u)), i};
  std::sort(angle.begin(), angle.end());
  for (const auto& a : angle) out.push_back(unique[a.second]);
  return true;
}

}  // namespace

void ConvexPolytope::add_face(std::span<const Vec3> points) {
  points_.insert(points_.end(), points.begin(), points.end());
  start_.push_back(static_cast<std::uint32_t>(points_.size()));
}

ConvexPolytope ConvexPolytope::box(const Box& b) {
  const Vec3 l = b.lo, h = b.hi;
  ConvexPolytope p;
  const Vec3 faces[6][4] = {
      {{l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, l.y, l.z}},  // z = lo, normal -z
      {{l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}},  // z = hi, normal +z
      {{l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}},  // y = lo, normal -y
      {{l.x, h.y, l.z}, {l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z}},  // y = hi, normal +y
      {{l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z}},  // x = lo, normal -x
      {{h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z}},  // x = hi, normal +x
  };
  for (const auto& f : faces) p.add_face(f);
  return p;
}

ConvexPolytope ConvexPolytope::clipped(const Plane& keep, double eps) const {
  ConvexPolytope out;
  clip_into(keep, eps, out);
  return out;
}

void ConvexPolytope::clip_into(const Plane& keep, double eps, ConvexPolytope& out) const {
  assert(&out != this);  // out is cleared before this polytope's faces are read
  bool any_front = false, any_back = false;
  for (const Vec3& v : points_) {
    const double d = keep.distance(v);
    any_front |= d > eps;
    any_back |= d < -eps;
  }
  if (!any_back) {
    out = *this;
    return;
  }
  out.points_.clear();
  out.start_.assign(1, 0);
  if (!any_front) return;
  out.points_.reserve(points_.size() + points_.size() / 2);
  thread_local ClipScratch scratch;
  scratch.on_plane.clear();
  for (std::size_t i = 0; i < face_count(); ++i) {
    const std::span<const Vec3> f = face(i);
    const Side side = classify(f, keep, eps);
    if (side == Side::Back) continue;
    if (side == Side::Spanning) {
      scratch.whole.verts.resize(f.size());
      for (std::size_t k = 0; k < f.size(); ++k) scratch.whole.verts[k] = Vertex{f[k]};
      // Polytope faces are never dropped as slivers: a thin face still bounds the volume.
      if (!front_part_into(scratch.whole, keep, 0.0, scratch.front)) continue;
      for (const Vertex& v : scratch.front.verts) out.points_.push_back(v.p);
    } else {
      out.points_.insert(out.points_.end(), f.begin(), f.end());
    }
    for (std::size_t k = out.start_.back(); k < out.points_.size(); ++k)
      if (std::abs(keep.distance(out.points_[k])) <= eps) scratch.on_plane.push_back(out.points_[k]);
    out.start_.push_back(static_cast<std::uint32_t>(out.points_.size()));
  }
  if (cap_polygon(scratch.on_plane, -keep.n, eps, scratch, out.points_))
    out.start_.push_back(static_cast<std::uint32_t>(out.points_.size()));
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
ConvexPolytope::SplitMeasure ConvexPolytope::measure_split(const Plane& plane, double eps, Measures what) const {
  const bool areas = what == Measures::VolumesAndAreas;
  // Each vertex's distance, snapped to 0 within eps, computed once, parallel to points_.
  thread_local std::vector<double> dist;
  dist.resize(points_.size());
  bool any_front = false, any_back = false;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    double d = plane.distance(points_[i]);
    if (std::abs(d) <= eps) d = 0;
    any_front |= d > 0;
    any_back |= d < 0;
    dist[i] = d;
  }
  if (!any_back) return {volume(), 0.0, areas ? surface_area() : 0.0, 0.0};
  if (!any_front) return {0.0, volume(), 0.0, areas ? surface_area() : 0.0};
  const Vec3 o = plane.n * -plane.d;
  Vec3 front_total, back_total;
  SplitMeasure m;
  for (std::size_t fi = 0; fi < face_count(); ++fi) {
    const std::span<const Vec3> f = face(fi);
    const std::size_t k = f.size();
    const double* fd = dist.data() + start_[fi];
    if (std::all_of(fd, fd + k, [](double x) { return x == 0; })) continue;
    NewellSum front{o, {}, {}, {}, {}}, back{o, {}, {}, {}, {}};
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t j = i + 1 == k ? 0 : i + 1;
      const Vec3& a = f[i];
      const double da = fd[i], db = fd[j];
      if (da >= 0) front.add(a);
      if (da <= 0) back.add(a);
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
        const Vec3 x = a + (f[j] - a) * (da / (da - db));
        front.add(x);
        back.add(x);
      }
    }
    const Vec3 nf = front.closed(), nb = back.closed();
    m.front_volume += dot(nf, front.point) / 6.0;
    m.back_volume += dot(nb, back.point) / 6.0;
    if (!areas) continue;
    front_total += nf;
    back_total += nb;
    m.front_area += 0.5 * length(nf);
    m.back_area += 0.5 * length(nb);
  }
  if (!areas) return m;
  m.front_area += 0.5 * length(front_total);
  m.back_area += 0.5 * length(back_total);
  return m;
}

double ConvexPolytope::volume() const {
  double v = 0;
  for (std::size_t i = 0; i < face_count(); ++i) v += dot(newell_normal(face(i)), face(i).front());
  return v / 6.0;
}

double ConvexPolytope::surface_area() const {
  double a = 0;
  for (std::size_t i = 0; i < face_count(); ++i) a += 0.5 * length(newell_normal(face(i)));
  return a;
}

ConvexPolytope::Section ConvexPolytope::top_section() const {
  for (std::size_t i = 0; i < face_count(); ++i) {
    const auto f = face(i);
    const Vec3 n = newell_normal(f);
    // Every other face of an extruded cell is vertical (n.z = 0) or faces down.
    if (!(n.z > 0)) continue;
    Section s{0.5 * length(n), 0};
    for (std::size_t k = 0; k < f.size(); ++k) s.perimeter += length(f[(k + 1) % f.size()] - f[k]);
    return s;
  }
  return {};
}

Box ConvexPolytope::bounds() const {
  Box b;
  for (const Vec3& p : points_) b.add(p);
  return b;
}

}  // namespace bsp
