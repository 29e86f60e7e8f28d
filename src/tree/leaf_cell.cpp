#include "tree/leaf_cell.h"

#include "geometry/segment2.h"

namespace bsp {

namespace {

Vec3 vertex_average(std::span<const Vec3> points) {
  Vec3 c;
  for (const Vec3& p : points) c += p;
  return c / static_cast<double>(points.size());
}

std::uint32_t group_of(const FragmentStore& frags, std::span<const std::uint32_t> groups, std::uint32_t id) {
  return groups.empty() ? 0 : groups[frags.source(id)];
}

}  // namespace

bool faces_into_cell(const FragmentStore& frags, const PlanePool& planes, std::uint32_t a, std::uint32_t b,
                     double eps) {
  const Plane pa = planes[frags.plane(a)];
  switch (frags.classify(b, pa, eps)) {
    case Side::Front: return true;
    case Side::Coplanar: return dot(planes[frags.plane(b)].n, pa.n) > 0;
    default: return false;
  }
}

std::optional<std::uint32_t> convexity_witness(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                                               const PlanePool& planes, double eps) {
  for (auto a : ids)
    for (auto b : ids)
      if (a != b && !faces_into_cell(frags, planes, a, b, eps)) return a;
  return std::nullopt;
}

bool one_group(std::span<const std::uint32_t> ids, const FragmentStore& frags, std::span<const std::uint32_t> groups) {
  for (auto id : ids)
    if (group_of(frags, groups, id) != group_of(frags, groups, ids.front())) return false;
  return true;
}

std::vector<Plane> group_separators(std::span<const std::uint32_t> ids, const FragmentStore& frags,
                                    std::span<const std::uint32_t> groups) {
  const std::uint32_t first = ids.front();
  std::uint32_t other = first;
  for (auto id : ids)
    if (group_of(frags, groups, id) != group_of(frags, groups, first)) {
      other = id;
      break;
    }
  const Vec3 a = vertex_average(frags.points(first)), b = vertex_average(frags.points(other));
  std::vector<Plane> out{Plane::through(a - b, (a + b) / 2.0)};
  if (frags.points(first).size() != 2 || frags.points(other).size() != 2) return out;
  for (std::uint32_t id : {first, other})
    for (const Vec3& p : frags.points(id))
      for (const auto& [dx, dy] : kSeparatorDirections)
        if (const auto line = line_through(p, p + Vec3{dx, dy, 0})) out.push_back(*line);
  return out;
}

bool parts_leafy(std::span<const std::uint32_t> ids, const FragmentStore& frags, const PlanePool& planes,
                 const Plane& plane, double eps) {
  bool front = false, back = false;
  for (auto id : ids) {
    switch (frags.classify(id, plane, eps)) {
      case Side::Front: front = true; break;
      case Side::Back: back = true; break;
      case Side::Spanning: return true;
      case Side::Coplanar: (dot(planes[frags.plane(id)].n, plane.n) > 0 ? front : back) = true; break;
    }
    if (front && back) return true;
  }
  return false;
}

}  // namespace bsp
