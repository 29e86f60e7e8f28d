// The exact kernel's split of convex polygons (geometry/plane_polygon.h). The input decodes to a
// polygon of grid points and up to four cutting planes through grid points (each coordinate either
// a small value, which makes vertices on a plane and parallel planes common, or any value within
// the grid's range). A polygon that is not convex and planar is refused by plane_polygon and
// skipped. For every cut that spans a piece, the two parts must
//  - be valid plane polygons (every vertex defined, strictly inside every other bound),
//  - have every vertex on their own side of the cut, decided exactly,
//  - share exactly the two vertices on the cut.
// Each part is cut again by the next plane, so bound lists grow and cuts meet earlier cuts.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include "geometry/grid.h"
#include "geometry/plane_polygon.h"

namespace {

using namespace bsp;

constexpr std::int64_t kGridMax = (std::int64_t{1} << kGridBits) - 1;

std::int64_t coordinate(FuzzedDataProvider& in) {
  if (in.ConsumeBool()) return in.ConsumeIntegralInRange<std::int64_t>(-4, 4);
  return in.ConsumeIntegralInRange<std::int64_t>(-kGridMax, kGridMax);
}

GridPoint point(FuzzedDataProvider& in) { return {coordinate(in), coordinate(in), coordinate(in)}; }

[[noreturn]] void violated(const char* what) {
  std::fprintf(stderr, "invariant violated: %s\n", what);
  std::abort();
}

int shared_vertices(const PlanePolygon& a, const PlanePolygon& b, PredicateCounters& counters) {
  int shared = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      shared += side_of_vertex(a.support, a.before(i), a.after(i), b.before(j), counters) == 0 &&
                side_of_vertex(a.support, a.before(i), a.after(i), b.after(j), counters) == 0;
  return shared;
}

void check_part(const PlanePolygon& part, const GridPlane& cut, int side, PredicateCounters& counters) {
  if (!is_valid(part, counters)) violated("a part is not a valid plane polygon");
  for (int s : vertex_sides(part, cut, counters))
    if (s * side < 0) violated("a vertex on the wrong side of the cut");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  std::vector<GridPoint> corners(in.ConsumeIntegralInRange<int>(3, 8));
  for (auto& c : corners) c = point(in);
  const auto start = plane_polygon(corners, 0);
  if (!start) return 0;
  PredicateCounters counters;
  if (!is_valid(*start, counters)) violated("plane_polygon made an invalid polygon");
  std::vector<PlanePolygon> pieces{*start};
  for (int cut = 0; cut < 4 && in.remaining_bytes() > 0; ++cut) {
    const auto plane = plane_through(point(in), point(in), point(in));
    if (!plane) continue;
    std::vector<PlanePolygon> next;
    for (const PlanePolygon& piece : pieces) {
      const PlaneSplit s = split(piece, *plane, counters);
      if (s.side != Side::Spanning) {
        next.push_back(piece);
        continue;
      }
      check_part(*s.front, *plane, 1, counters);
      check_part(*s.back, *plane, -1, counters);
      if (shared_vertices(*s.front, *s.back, counters) != 2) violated("the parts do not share the cut's two vertices");
      next.push_back(*s.front);
      next.push_back(*s.back);
    }
    pieces = std::move(next);
  }
  return 0;
}
