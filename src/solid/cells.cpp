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

void add_cap(Cell& cell, std::vector<Vec3>& cut, const Plane& outward, Ref node) {
  // Each cut point comes once from each face through it, bit for bit (edge_cut): keep one.
  std::sort(cut.begin(), cut.end(), [](const Vec3& a, const Vec3& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  });
  cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
  if (cut.size() < 3) return;
  Vec3 c;
  for (const Vec3& p : cut) c += p;
  c = c / static_cast<double>(cut.size());
  const Vec3 n = outward.n;
  const Vec3 u = normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
  const Vec3 v = cross(n, u);
  std::vector<std::pair<double, Vec3>> by_angle;
  for (const Vec3& p : cut) by_angle.push_back({std::atan2(dot(p - c, v), dot(p - c, u)), p});
  std::sort(by_angle.begin(), by_angle.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  cut.clear();
  for (const auto& a : by_angle) cut.push_back(a.second);
  cell.faces.add(cut);
  cell.outward.push_back(outward);
  cell.cut_by.push_back(node);
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
  std::vector<Vec3> f, b, cut;
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) {
    const std::span<const Vec3> loop = cell.faces[i];
    split_loop(loop, plane, 0.0, f, b);
    if (!f.empty()) front.faces.add(f), front.outward.push_back(cell.outward[i]), front.cut_by.push_back(cell.cut_by[i]);
    if (!b.empty()) back.faces.add(b), back.outward.push_back(cell.outward[i]), back.cut_by.push_back(cell.cut_by[i]);
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Vec3& p = loop[k];
      const Vec3& q = loop[k + 1 == loop.size() ? 0 : k + 1];
      const double dp = plane.distance(p), dq = plane.distance(q);
      if (dp == 0) cut.push_back(p);
      if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) cut.push_back(edge_cut(p, q, dp, dq));
    }
  }
  std::vector<Vec3> cap = cut;
  add_cap(front, cap, plane.flipped(), node);
  add_cap(back, cut, plane, node);
}

double cell_volume(const Cell& cell) {
  double v = 0;
  for (std::uint32_t i = 0; i < cell.faces.size(); ++i) v += dot(newell_normal(cell.faces[i]), cell.faces[i].front());
  return v / 6.0;
}

}  // namespace bsp
