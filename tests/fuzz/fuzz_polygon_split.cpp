// Classification and splitting of convex polygons by arbitrary planes. The input decodes to a plane
// and a polygon (each number either a small grid value, which makes vertices on the plane common,
// or a raw double; NaN, infinity and magnitudes outside [1e-6, 1e6] are skipped). The polygon is
// first made convex and planar by append_clean_polygon, as the mesh reader does. For every piece
// that spans the plane, split must give parts that
//  - lie on their side of the plane within plane_eps,
//  - have no NaN coordinate,
//  - together with the dropped slivers keep the piece's area, within a tolerance scaled by the
//    input's extent and its distance from the origin (Newell's area is computed from absolute
//    coordinates, so its rounding grows with them).
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "geometry/polygon.h"
#include "geometry/tolerance.h"
#include "io/polygon_cleanup.h"
#include "scene/scene.h"

namespace {

using namespace bsp;

std::optional<double> number(FuzzedDataProvider& in) {
  if (in.ConsumeBool()) return in.ConsumeIntegralInRange<int>(-16, 16) / 4.0;
  const double x = in.ConsumeFloatingPoint<double>();
  if (!std::isfinite(x) || std::abs(x) > 1e6 || (x != 0 && std::abs(x) < 1e-6)) return std::nullopt;
  return x;
}

std::optional<Vec3> point(FuzzedDataProvider& in) {
  const auto x = number(in), y = number(in), z = number(in);
  if (!x || !y || !z) return std::nullopt;
  return Vec3{*x, *y, *z};
}

[[noreturn]] void violated(const char* what, double a, double b) {
  std::fprintf(stderr, "invariant violated: %s (%.17g vs %.17g)\n", what, a, b);
  std::abort();
}

void check_part(const std::optional<Polygon>& part, const Plane& plane, double eps, double sign) {
  if (!part) return;
  for (const auto& v : part->verts) {
    if (!is_finite(v.p) || !std::isfinite(v.u) || !std::isfinite(v.v)) violated("NaN in a part", 0, 0);
    if (sign * plane.distance(v.p) < -eps) violated("vertex on the wrong side", plane.distance(v.p), eps);
  }
}

void check_split(const Polygon& piece, const Plane& plane, double eps, double area_tol) {
  if (classify(piece, plane, eps) != Side::Spanning) return;
  const SplitResult r = split(piece, plane, eps);
  check_part(r.front, plane, eps, 1.0);
  check_part(r.back, plane, eps, -1.0);
  const double kept = (r.front ? area(*r.front) : 0.0) + (r.back ? area(*r.back) : 0.0) + r.dropped_area;
  if (!(std::abs(kept - area(piece)) <= area_tol)) violated("area not conserved", kept, area(piece));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const auto normal = point(in);
  const auto offset = number(in);
  if (!normal || !offset || !(length(*normal) > 0)) return 0;
  const Plane plane{normalize(*normal), *offset};
  Polygon poly;
  for (int k = in.ConsumeIntegralInRange<int>(3, 8); k > 0; --k) {
    const auto p = point(in);
    if (!p) return 0;
    poly.verts.push_back({*p, in.ConsumeIntegralInRange<int>(0, 4) / 4.0, in.ConsumeIntegralInRange<int>(0, 4) / 4.0});
  }
  Box box;
  double far = 0;
  for (const auto& v : poly.verts) box.add(v.p), far = std::max({far, std::abs(v.p.x), std::abs(v.p.y), std::abs(v.p.z)});
  const double extent = box.diagonal();
  const double eps = Tolerance::for_extent(extent).plane_eps;
  const double area_tol = 1e-9 * extent * (extent + far);
  std::vector<Polygon> pieces;
  SceneLoadStats stats;
  append_clean_polygon(std::move(poly), eps, pieces, stats);
  for (const auto& piece : pieces) check_split(piece, plane, eps, area_tol);
  return 0;
}
