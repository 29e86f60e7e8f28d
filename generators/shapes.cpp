#include "shapes.h"

#include <algorithm>

namespace bsp {

Polygon triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return {{{a, 0, 0}, {b, 1, 0}, {c, 0, 1}}, 0}; }

Polygon quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return {{{a, 0, 0}, {b, 1, 0}, {c, 1, 1}, {d, 0, 1}}, 0};
}

Polygon parallelogram(const Vec3& origin, const Vec3& u, const Vec3& v) {
  return quad(origin, origin + u, origin + u + v, origin + v);
}

Polygon flipped(Polygon poly) {
  std::reverse(poly.verts.begin(), poly.verts.end());
  return poly;
}

std::vector<Polygon> generate_items(std::size_t items,
                                    const std::function<void(std::size_t, std::vector<Polygon>&)>& make) {
  std::vector<std::vector<Polygon>> parts(items);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < items; ++i) make(i, parts[i]);
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  std::vector<Polygon> out;
  out.reserve(total);
  for (auto& part : parts)
    for (auto& poly : part) {
      poly.source = static_cast<std::uint32_t>(out.size());
      out.push_back(std::move(poly));
    }
  return out;
}

std::uint64_t seed_of(const ParamSet& p) { return static_cast<std::uint64_t>(p.integer("seed")); }
std::size_t count_of(const ParamSet& p) { return static_cast<std::size_t>(p.integer("n")); }

}  // namespace bsp
