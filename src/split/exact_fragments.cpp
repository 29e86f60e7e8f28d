#include "split/exact_fragments.h"

#include <stdexcept>
#include <utility>

namespace bsp {

namespace {

// The rounded copy of a fragment: each vertex from its cofactors (x = C_0 / C_3 and so on, in grid
// units), an estimate for splitters only.
Polygon rounded_polygon(std::span<const VertexCofactors> cofactors, const Grid& grid, std::uint32_t source) {
  Polygon out;
  out.source = source;
  out.verts.reserve(cofactors.size());
  for (const VertexCofactors& c : cofactors)
    out.verts.push_back({grid.origin() + Vec3{c.c[0] / c.c[3], c.c[1] / c.c[3], c.c[2] / c.c[3]} * grid.step()});
  return out;
}

}  // namespace

std::uint32_t ExactFragments::store(PlanePolygon poly, std::vector<Vertex> verts) {
  std::vector<VertexCofactors> cofactors;
  cofactors.reserve(verts.size());
  for (const Vertex& v : verts) cofactors.push_back(v.cofactors);
  const std::uint32_t support = planes_.add(poly.support);
  const std::uint32_t id = rounded_.add(rounded_polygon(cofactors, planes_.grid(), poly.source), support);
  if (id >= poly_.size()) {
    poly_.resize(id + 1);
    verts_.resize(id + 1);
  }
  poly_[id] = std::move(poly);
  verts_[id] = std::move(verts);
  return id;
}

std::uint32_t ExactFragments::add(PlanePolygon poly, std::span<const GridPoint> corners) {
  std::vector<Vertex> verts(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto c = vertex_cofactors(poly.support, poly.before(i), poly.after(i), counters_.predicates);
    if (!c) throw std::invalid_argument("a plane polygon's vertex is not defined");
    verts[i].cofactors = *c;
    if (!corners.empty()) {
      verts[i].corner = corners[i];
      verts[i].on_grid = true;
    }
  }
  return store(std::move(poly), std::move(verts));
}

void ExactFragments::release(std::uint32_t id) {
  rounded_.release(id);
  poly_[id] = {};
  verts_[id] = {};
}

int ExactFragments::vertex_side(std::uint32_t id, std::size_t i, const GridPlane& plane, const PlaneApprox& approx) const {
  const Vertex& v = verts_[id][i];
  if (const auto f = detail::filtered_side(v.cofactors, approx); f.decided) {
    ++counters_.predicates.filtered;
    return f.sign;
  }
  if (v.on_grid) {
    ++counters_.on_grid;
    return plane.side(v.corner);
  }
  const PlanePolygon& poly = poly_[id];
  return side_of_vertex(poly.support, poly.before(i), poly.after(i), plane, counters_.predicates);
}

Side ExactFragments::sides(std::uint32_t id, std::uint32_t plane, bool all) const {
  const std::size_t k = poly_[id].size();
  sides_.assign(k, 0);
  if (PlanePool::coplanar(plane, rounded_.plane(id))) {
    ++counters_.coplanar_by_index;
    return Side::Coplanar;
  }
  const GridPlane p = planes_[plane];
  const PlaneApprox approx = planes_.approx(plane);
  bool front = false, back = false;
  for (std::size_t i = 0; i < k; ++i) {
    sides_[i] = vertex_side(id, i, p, approx);
    front |= sides_[i] > 0;
    back |= sides_[i] < 0;
    if (front && back && !all) return Side::Spanning;
  }
  if (front && back) return Side::Spanning;
  if (front) return Side::Front;
  if (back) return Side::Back;
  return Side::Coplanar;  // every vertex on a plane that is not its support: impossible for a polygon
}

Side ExactFragments::classify(std::uint32_t id, std::uint32_t plane) const { return sides(id, plane, false); }

void ExactFragments::count_sides(std::span<const std::uint32_t> ids, std::span<const std::uint32_t> planes,
                                 std::span<SideCounts> out) const {
  for (auto id : ids)
    for (std::size_t j = 0; j < planes.size(); ++j) switch (classify(id, planes[j])) {
        case Side::Front: ++out[j].front; break;
        case Side::Back: ++out[j].back; break;
        case Side::Coplanar: ++out[j].coplanar; break;
        case Side::Spanning: ++out[j].spanning; break;
      }
}

std::uint32_t ExactFragments::add_part(PolygonPart part, const std::vector<Vertex>& from) {
  const PlanePolygon& poly = part.poly;
  std::vector<Vertex> verts(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) {
    if (part.origin[i] != kNewVertex) {
      verts[i] = from[part.origin[i]];
      continue;
    }
    const auto c = vertex_cofactors(poly.support, poly.before(i), poly.after(i), counters_.predicates);
    if (!c) throw std::logic_error("a split made an undefined vertex");
    verts[i].cofactors = *c;
  }
  return store(std::move(part.poly), std::move(verts));
}

ExactFragments::Parts ExactFragments::split(std::uint32_t id, std::uint32_t plane) {
  if (sides(id, plane, true) != Side::Spanning) throw std::logic_error("split of a fragment that does not span the plane");
  const std::vector<int> s = sides_;
  const GridPlane cut = planes_[plane];
  PolygonPart front = part_of(poly_[id], s, 1, cut);
  PolygonPart back = part_of(poly_[id], s, -1, cut);
  const std::vector<Vertex> from = std::move(verts_[id]);
  release(id);
  Parts parts;
  parts.front = add_part(std::move(front), from);
  parts.back = add_part(std::move(back), from);
  return parts;
}

}  // namespace bsp
