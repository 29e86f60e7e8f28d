#include "split/parallel_groups.h"

#include <algorithm>
#include <cmath>

#include "geometry/point_grid.h"

namespace bsp {

namespace {

constexpr std::uint32_t kNoGroup = 0xffffffffu;

}  // namespace

ParallelGroups group_parallel(std::span<const Vec3> normals, double angle) {
  // Unit vectors at most `angle` apart are at most this chord apart, so in neighbouring cells.
  const double chord = 2.0 * std::sin(angle / 2.0);
  const double chord2 = chord * chord;
  PointGrid grid(chord);
  ParallelGroups out;
  out.group_of.reserve(normals.size());
  for (const Vec3& n : normals) {
    std::uint32_t found = kNoGroup;
    const auto consider = [&](std::uint32_t g) {
      // Compared as chords rather than cosines: cos(angle) rounds to 1 for tiny angles.
      const Vec3& r = out.representative[g];
      const Vec3 a = n - r, b = n + r;
      if (g < found && std::min(dot(a, a), dot(b, b)) <= chord2) found = g;
    };
    grid.around(n, consider);
    grid.around(-n, consider);
    if (found == kNoGroup) {
      found = static_cast<std::uint32_t>(out.size.size());
      out.size.push_back(0);
      out.representative.push_back(n);
      grid.insert(n, found);
    }
    ++out.size[found];
    out.group_of.push_back(found);
  }
  return out;
}

}  // namespace bsp
