// orthogonal-stacks: the n^{3/2} lower-bound construction for orthogonal objects. Three families of
// k^2 long thin axis-parallel rectangles, one family along each axis, on three mutually offset
// k x k lattices, so that the lattice of k^3 unit cells is caged from all three directions:
//   along x: the strip in the plane z = Lz[j], y in [Ly[i] - w, Ly[i] + w];
//   along y: the strip in the plane x = Hx[i], z in [Hz[j] - w, Hz[j] + w];
//   along z: the strip in the plane y = Hy[j], x in [Lx[i] - w, Lx[i] + w];
// for i, j = 0..k-1, each spanning [-1/2, k - 1/2] along its axis, where La[i] = i and
// Ha[i] = i + 1/2 on axis a, each shifted by a random jitter per lattice line (the seed). Strips of
// one family in one layer stay exactly coplanar, so a family's k^2 strips lie in k planes, each of
// which cuts all k^2 strips of one other family: k^3 = (n/3)^{3/2} fragments for an autopartition
// that uses them. (A jitter per strip would give every strip its own plane and make autopartitions
// quadratic, hiding the n^{3/2} structure.)
//
// Paterson and Yao ("Optimal binary space partitions for orthogonal objects", J. Algorithms 13,
// 1992, pp. 99-113; Warwick research report CS-RR-158, 1990) show that n axis-parallel segments or
// rectangles in R^3 always have a BSP of O(n^{3/2}) fragments and that this is optimal: some sets
// need Omega(n^{3/2}). Hershberger and Suri ("Binary space partitions for 3D subdivisions", SODA
// 2003) restate it as Theta(n^{3/2}) for rectangles. The lower-bound sets are lattices of
// axis-parallel segments of this kind (k^2 per axis, each of the k^3 cells caged, so
// Omega(k^3) = Omega(n^{3/2}) fragments); the exact offsets above are ours, reconstructed from that
// argument rather than copied from the paper, whose text was not available here. Each segment is
// thickened into a strip of half-width w so the scene is polygons.
//
// Disjointness: two families differ by 1/2 in the coordinate that separates them, less twice the
// jitter; that exceeds w, so no two strips meet.
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr double kHalfWidth = 0.1;  // strip half-width w (lattice spacing 1)
constexpr double kJitter = 0.1;     // largest random shift of a lattice line
static_assert(0.5 - 2 * kJitter > kHalfWidth, "families would touch");

// Line i of one axis at i + offset + jitter.
std::vector<double> lattice_lines(std::size_t k, double offset, std::uint64_t stream) {
  std::vector<double> lines(k);
  for (std::size_t i = 0; i < k; ++i)
    lines[i] = static_cast<double>(i) + offset + kJitter * Rng(stream_seed(stream, i)).uniform(-1, 1);
  return lines;
}

std::vector<Polygon> make(const ParamSet& p) {
  const auto k = std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(static_cast<double>(count_of(p)) / 3)));
  const std::uint64_t seed = seed_of(p);
  std::vector<double> L[3], H[3];
  for (std::uint64_t a = 0; a < 3; ++a) {
    L[a] = lattice_lines(k, 0.0, stream_seed(seed, 2 * a));
    H[a] = lattice_lines(k, 0.5, stream_seed(seed, 2 * a + 1));
  }
  const double lo = -0.5, len = static_cast<double>(k), w = kHalfWidth;
  return generate_items(3 * k * k, [&](std::size_t item, std::vector<Polygon>& out) {
    const std::size_t axis = item / (k * k), i = item % k, j = (item / k) % k;
    if (axis == 0)  // plane z = Lz[j], facing +z
      out.push_back(parallelogram({lo, L[1][i] - w, L[2][j]}, {len, 0, 0}, {0, 2 * w, 0}));
    else if (axis == 1)  // plane x = Hx[i], facing +x
      out.push_back(parallelogram({H[0][i], lo, H[2][j] - w}, {0, len, 0}, {0, 0, 2 * w}));
    else  // plane y = Hy[j], facing +y
      out.push_back(parallelogram({L[0][i] - w, H[1][j], lo}, {0, 0, len}, {2 * w, 0, 0}));
  });
}

}  // namespace

GeneratorInfo orthogonal_stacks_generator() {
  return {"orthogonal-stacks",
          "Paterson-Yao orthogonal lower bound: three caging families of thin axis-parallel rectangles where every "
          "BSP has Theta(n^{3/2}) fragments",
          "3 k^2 rectangles, k = max(1, floor(sqrt(n / 3))): k^2 along each axis",
          {n_param(300, "largest number of rectangles (rounded down to 3 k^2)"), seed_param()},
          make};
}

}  // namespace bsp
