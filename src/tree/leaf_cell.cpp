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
                                    std::span<const std::uint32_t> groups, double eps) {
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      const std::uint32_t a = ids[i], b = ids[j];
      if (group_of(frags, groups, a) == group_of(frags, groups, b)) continue;
      const Vec3 ca = vertex_average(frags.points(a)), cb = vertex_average(frags.points(b));
      if (length(ca - cb) <= eps) continue;  // the same place: no plane parts them
      std::vector<Plane> out{Plane::through(ca - cb, (ca + cb) / 2.0)};
      if (frags.points(a).size() != 2 || frags.points(b).size() != 2) return out;
      for (std::uint32_t id : {a, b})
        for (const Vec3& p : frags.points(id))
          for (const auto& [dx, dy] : kSeparatorDirections)
            if (const auto line = line_through(p, p + Vec3{dx, dy, 0})) out.push_back(*line);
      return out;
    }
  return {};
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
