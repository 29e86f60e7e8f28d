#include "geometry/convex_loop.h"

#include <algorithm>
#include <cmath>

#include "geometry/tolerance.h"

namespace bsp {

std::uint32_t LoopPool::add(std::span<const Vec3> loop) {
  points.insert(points.end(), loop.begin(), loop.end());
  start.push_back(static_cast<std::uint32_t>(points.size()));
  return static_cast<std::uint32_t>(start.size() - 2);
}

void split_loop(std::span<const Vec3> loop, const Plane& plane, double eps, std::vector<Vec3>& front,
                std::vector<Vec3>& back) {
  front.clear();
  back.clear();
  const std::size_t k = loop.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = loop[i];
    const Vec3& b = loop[i + 1 == k ? 0 : i + 1];
    const double da = plane.distance(a), db = plane.distance(b);
    if (da >= -eps) front.push_back(a);
    if (da <= eps) back.push_back(a);
    if ((da > eps && db < -eps) || (da < -eps && db > eps)) {
      const Vec3 x = edge_cut(a, b, da, db);
      front.push_back(x);
      back.push_back(x);
    }
  }
  if (front.size() < 3) front.clear();
  if (back.size() < 3) back.clear();
}

Vec3 edge_cut(const Vec3& a, const Vec3& b, double da, double db) {
  const bool a_first = a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  return a_first ? a + (b - a) * (da / (da - db)) : b + (a - b) * (db / (db - da));
}

std::vector<Vec3> plane_in_box(const Plane& plane, const Box& box) {
  // A square on the plane, centred at the box centre's projection and larger than the box, then
  // clipped by the box's six faces.
  const Vec3 n = plane.n;
  const Vec3 c = box.center() - n * plane.distance(box.center());
  const Vec3 u = normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
  const Vec3 v = cross(n, u);
  const double r = 2.0 * std::max(box.diagonal(), 1e-300);
  std::vector<Vec3> loop = {c - u * r - v * r, c + u * r - v * r, c + u * r + v * r, c - u * r + v * r};
  const Plane faces[6] = {{{1, 0, 0}, -box.lo.x}, {{-1, 0, 0}, box.hi.x}, {{0, 1, 0}, -box.lo.y},
                          {{0, -1, 0}, box.hi.y}, {{0, 0, 1}, -box.lo.z}, {{0, 0, -1}, box.hi.z}};
  std::vector<Vec3> inside, outside;
  for (const Plane& f : faces) {
    split_loop(loop, f, 0.0, inside, outside);
    loop.swap(inside);
    if (loop.empty()) break;
  }
  return loop;
}

Side classify_loop(std::span<const Vec3> loop, const Plane& own, const Plane& plane, double eps) {
  const Side side = classify(loop, plane, eps);
  if (side != Side::Coplanar || std::abs(dot(own.n, plane.n)) >= 1 - kParallelCosineSlack) return side;
  const Side exact = classify(loop, plane, 0.0);
  return exact == Side::Coplanar ? Side::Front : exact;
}

bool mostly_in_front(std::span<const Vec3> loop, const Plane& plane) {
  double most_front = 0, most_back = 0;
  for (const Vec3& p : loop) {
    const double d = plane.distance(p);
    most_front = std::max(most_front, d);
    most_back = std::max(most_back, -d);
  }
  return most_front >= most_back;
}

}  // namespace bsp
