#include "geometry/segment2.h"

#include <algorithm>
#include <cmath>

namespace bsp {

std::optional<Plane> line_through(const Vec3& a, const Vec3& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len = std::hypot(dx, dy);
  if (len == 0.0) return std::nullopt;
  const Vec3 n{dy / len, -dx / len, 0.0};  // right of a → b
  return Plane{n, -(n.x * a.x + n.y * a.y)};
}

bool is_segment(const Polygon& poly) {
  return poly.verts.size() == 2 && poly.verts[0].p.z == 0.0 && poly.verts[1].p.z == 0.0;
}

bool all_segments(std::span<const Polygon> polys) {
  return !polys.empty() && std::all_of(polys.begin(), polys.end(), [](const Polygon& p) { return is_segment(p); });
}

double segment_length(std::span<const Vec3> points) {
  return std::hypot(points[1].x - points[0].x, points[1].y - points[0].y);
}

double measure(const Polygon& poly) {
  if (poly.verts.size() == 2) return std::hypot(poly.verts[1].p.x - poly.verts[0].p.x, poly.verts[1].p.y - poly.verts[0].p.y);
  return poly.verts.size() >= 3 ? area(poly) : 0.0;
}

bool is_thin(const Polygon& poly, double eps) { return is_segment(poly) ? measure(poly) < eps : is_sliver(poly, eps); }

Vec3 intersect(const Plane& l, const Vec3& a, const Vec3& b) {
  // In coordinates centred at a: there l = (a', b', c) with c = l·(a, 1), and l' = (0, 0, 1) × (e, 1)
  // = (-e.y, e.x, 0) with e = b - a, free of cancellation; a × b in world coordinates cancels its
  // large terms for a short segment far from the origin and moves the line by more than plane_eps.
  const Vec3 lh{l.n.x, l.n.y, l.distance(Vec3{a.x, a.y, 0.0})};
  const Vec3 mh{-(b.y - a.y), b.x - a.x, 0.0};
  const Vec3 x = cross(lh, mh);
  return {a.x + x.x / x.z, a.y + x.y / x.z, 0.0};
}

namespace {

// The vertex at x on a → b, its texture coordinates interpolated by distance along the segment.
Vertex vertex_at(const Vertex& a, const Vertex& b, const Vec3& x) {
  const double len = std::hypot(b.p.x - a.p.x, b.p.y - a.p.y);
  const double t = len > 0 ? std::hypot(x.x - a.p.x, x.y - a.p.y) / len : 0.0;
  return {x, a.u + t * (b.u - a.u), a.v + t * (b.v - a.v)};
}

bool keep_or_drop(Polygon& part, double eps, SplitKept& kept) {
  const double len = std::hypot(part.verts[1].p.x - part.verts[0].p.x, part.verts[1].p.y - part.verts[0].p.y);
  if (len >= eps) return true;
  ++kept.dropped;
  kept.dropped_area += len;
  return false;
}

}  // namespace

SplitKept split_segment_into(const Polygon& seg, const Plane& line, double eps, Polygon& front, Polygon& back) {
  const Vertex& v0 = seg.verts[0];
  const Vertex& v1 = seg.verts[1];
  const Vertex x = vertex_at(v0, v1, intersect(line, v0.p, v1.p));
  const bool v0_front = line.distance(v0.p) > 0;
  Polygon& first = v0_front ? front : back;
  Polygon& second = v0_front ? back : front;
  first.verts.assign({v0, x});
  second.verts.assign({x, v1});
  front.source = back.source = seg.source;
  SplitKept kept;
  kept.front = keep_or_drop(front, eps, kept);
  kept.back = keep_or_drop(back, eps, kept);
  return kept;
}

std::vector<Polygon> extruded(std::span<const Polygon> segments, double height) {
  std::vector<Polygon> walls;
  walls.reserve(segments.size());
  for (const Polygon& s : segments) {
    const Vertex& a = s.verts[0];
    const Vertex& b = s.verts[1];
    walls.push_back({{a, b, {b.p + Vec3{0, 0, height}, b.u, 1}, {a.p + Vec3{0, 0, height}, a.u, 1}}, s.source});
  }
  return walls;
}

}  // namespace bsp
