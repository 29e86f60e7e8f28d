#include "geometry/polygon.h"

#include <algorithm>
#include <cmath>

namespace bsp {

namespace {

template <class Range, class At>
Vec3 newell_range(const Range& v, At at) {
  Vec3 n;
  for (std::size_t i = 0, k = v.size(); i < k; ++i) {
    const Vec3& a = at(v[i]);
    const Vec3& b = at(v[(i + 1) % k]);
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// Lambdas, not functions: each has its own type, so the templates inline them.
constexpr auto vertex_position = [](const Vertex& v) -> const Vec3& { return v.p; };
constexpr auto itself = [](const Vec3& p) -> const Vec3& { return p; };

}  // namespace

Vec3 newell_normal(const Polygon& poly) { return newell_range(poly.verts, vertex_position); }
Vec3 newell_normal(std::span<const Vec3> points) { return newell_range(points, itself); }

double area(const Polygon& poly) { return 0.5 * length(newell_normal(poly)); }

Vec3 centroid(const Polygon& poly) {
  Vec3 c;
  for (const auto& v : poly.verts) c += v.p;
  return poly.verts.empty() ? c : c / static_cast<double>(poly.verts.size());
}

std::optional<Plane> supporting_plane(const Polygon& poly) {
  const Vec3 n = newell_normal(poly);
  const double len = length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return std::nullopt;
  return Plane::through(n / len, centroid(poly));
}

double longest_edge(const Polygon& poly) {
  double best = 0.0;
  const auto& v = poly.verts;
  for (std::size_t i = 0, k = v.size(); i < k; ++i) best = std::max(best, length(v[(i + 1) % k].p - v[i].p));
  return best;
}

namespace {

// Both classifications for any vertex range; `at` gives a vertex's position.
template <class Range, class At>
Side classify_range(const Range& verts, At at, const Plane& plane, double eps) {
  bool front = false, back = false;
  for (const auto& v : verts) {
    const double d = plane.distance(at(v));
    front |= d > eps;
    back |= d < -eps;
  }
  if (front && back) return Side::Spanning;
  if (front) return Side::Front;
  if (back) return Side::Back;
  return Side::Coplanar;
}

template <class Range, class At>
bool in_front_or_on_range(const Range& verts, At at, const Plane& plane, double eps) {
  for (const auto& v : verts)
    if (plane.distance(at(v)) < -eps) return false;
  return true;
}

}  // namespace

Side classify(const Polygon& poly, const Plane& plane, double eps) {
  return classify_range(poly.verts, vertex_position, plane, eps);
}

Side classify(std::span<const Vec3> points, const Plane& plane, double eps) {
  return classify_range(points, itself, plane, eps);
}

bool in_front_or_on(const Polygon& poly, const Plane& plane, double eps) {
  return in_front_or_on_range(poly.verts, vertex_position, plane, eps);
}

bool in_front_or_on(std::span<const Vec3> points, const Plane& plane, double eps) {
  return in_front_or_on_range(points, itself, plane, eps);
}

double merge_close_vertices(Polygon& poly, double eps) {
  auto& v = poly.verts;
  const std::size_t k = v.size();
  if (k < 2) return 0.0;
  // Nothing merges unless two cyclically adjacent vertices are within eps: the common case costs
  // one pass and no area.
  bool close = length(v.back().p - v.front().p) <= eps;
  for (std::size_t i = 1; i < k && !close; ++i) close = length(v[i].p - v[i - 1].p) <= eps;
  if (!close) return 0.0;
  const double before = k >= 3 ? area(poly) : 0.0;
  std::size_t w = 1;  // v[0, w) kept, each more than eps from the one kept before it
  for (std::size_t i = 1; i < k; ++i)
    if (length(v[i].p - v[w - 1].p) > eps) v[w++] = v[i];
  while (w > 1 && length(v[w - 1].p - v[0].p) <= eps) --w;
  v.resize(w);
  return before - (w >= 3 ? area(poly) : 0.0);
}

bool is_sliver(const Polygon& poly, double eps) {
  if (poly.verts.size() < 3) return true;
  const double edge = longest_edge(poly);
  return !(edge > 0.0) || area(poly) / edge < eps;
}

namespace {

Vertex interpolate(const Vertex& a, const Vertex& b, double t) {
  return {lerp(a.p, b.p, t), a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t};
}

// Keeps a part, or drops it as a sliver and records that; true when kept.
bool keep_or_drop(Polygon& part, double eps, SplitKept& out) {
  out.dropped_area += merge_close_vertices(part, eps);
  if (!is_sliver(part, eps)) return true;
  ++out.dropped;
  out.dropped_area += part.verts.size() >= 3 ? area(part) : 0.0;
  return false;
}

}  // namespace

namespace {

// The parts of a polygon on either side of the plane, into `front` and, unless null, `back`.
// eps decided that the polygon spans the plane; the cut itself goes by the true sign of each
// distance, so the two parts partition the polygon exactly. (Sending every vertex within eps to
// both parts would make them overlap wherever two such vertices are adjacent.)
void cut(const Polygon& poly, const Plane& plane, Polygon& front, Polygon* back) {
  const std::size_t k = poly.verts.size();
  front.verts.clear();
  front.source = poly.source;
  if (back) {
    back->verts.clear();
    back->source = poly.source;
  }
  double di = k > 0 ? plane.distance(poly.verts[0].p) : 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = (i + 1) % k;
    const double dj = plane.distance(poly.verts[j].p);
    const Vertex& a = poly.verts[i];
    if (di >= 0) front.verts.push_back(a);
    if (di <= 0 && back) back->verts.push_back(a);
    if ((di > 0 && dj < 0) || (di < 0 && dj > 0)) {
      const Vertex x = interpolate(a, poly.verts[j], di / (di - dj));
      front.verts.push_back(x);
      if (back) back->verts.push_back(x);
    }
    di = dj;
  }
}

}  // namespace

SplitKept split_into(const Polygon& poly, const Plane& plane, double eps, Polygon& front, Polygon& back) {
  cut(poly, plane, front, &back);
  SplitKept kept;
  kept.front = keep_or_drop(front, eps, kept);
  kept.back = keep_or_drop(back, eps, kept);
  return kept;
}

bool front_part_into(const Polygon& poly, const Plane& plane, double eps, Polygon& front) {
  cut(poly, plane, front, nullptr);
  SplitKept unused;
  return keep_or_drop(front, eps, unused);
}

SplitResult split(const Polygon& poly, const Plane& plane, double eps) {
  Polygon front, back;
  const SplitKept kept = split_into(poly, plane, eps, front, back);
  SplitResult out;
  out.dropped = kept.dropped;
  out.dropped_area = kept.dropped_area;
  if (kept.front) out.front = std::move(front);
  if (kept.back) out.back = std::move(back);
  return out;
}

double enclosed_volume(std::span<const Polygon> polys) {
  double six = 0;
  for (const Polygon& p : polys)
    for (std::size_t i = 1; i + 1 < p.verts.size(); ++i) six += dot(p.verts[0].p, cross(p.verts[i].p, p.verts[i + 1].p));
  return six / 6;
}

}  // namespace bsp
