// near-degenerate: a scene built to break tolerance handling (geometry/tolerance.h). Two huge quads
// at z = -far and z = +far, spanning [-far, far]^2, fix the scene box to [-far, far]^3, so the
// build's tolerance is known in advance: eps = plane_eps = 1e-9 * diagonal. Inside the unit cube,
// motifs of four polygons each, one per grid cell, cycle through six kinds whose features are a few
// eps wide, placed on both sides of the tolerance:
//   0 slivers: long triangles of width 0.5, 1.5, 3 and 20 eps (the first two are narrower than the
//     sliver threshold and are dropped by the build; the others survive);
//   1 near-coplanar: overlapping quads at heights 0, 0.5 eps (facing the other way), 2.5 eps, and
//     one tilted from -1.5 to +1.5 eps across its width, which spans the others' planes by a hair;
//   2 T-junctions and shared edges: a floor of three coplanar quads where two share an edge whose
//     end lies inside the third's edge, and a wall whose bottom edge lies on the floor;
//   3 near-flat fan: four triangles around an apex raised 0.5 to 4.5 eps above their base square,
//     sharing edges at dihedral angles of a few eps;
//   4 near-touching vertices: a quad and three upright triangles whose lowest vertex is 0.3 eps
//     above, 0.6 eps below and 1.5 eps above the quad's plane;
//   5 tiny polygons: triangles with legs of 0.001, 0.5, 4 and 50 eps, down to far below the tolerance,
//     in the same scene as the huge quads' coordinates of magnitude `far`.
// The build must survive all of it, and its counters say what it dropped.
#include <cmath>

#include "catalog.h"
#include "common/rng.h"
#include "geometry/tolerance.h"
#include "shapes.h"

namespace bsp {

namespace {

constexpr std::size_t kKinds = 6;
constexpr double kMargin = 0.1;  // motif inset within its cell, as a fraction of the cell side

struct Motif {
  Vec3 o;        // corner of the motif's box
  double L;      // its side
  double eps;    // the scene's plane tolerance
  Rng rng;
  std::vector<Polygon>& out;

  Vec3 at(double x, double y, double z) const { return o + Vec3{x, y, z}; }
};

void slivers(Motif& m) {
  const double widths[4] = {0.5, 1.5, 3, 20};
  for (int q = 0; q < 4; ++q) {
    const double z = (q + 0.5) * m.L / 4, y = m.L * m.rng.uniform(0.1, 0.9), apex = m.L * m.rng.uniform(0.2, 0.8);
    m.out.push_back(triangle(m.at(0, y, z), m.at(m.L, y, z), m.at(apex, y + widths[q] * m.eps, z)));
  }
}

void near_coplanar(Motif& m) {
  const double z = m.L / 2, e = m.eps;
  auto shifted = [&](double lift0, double lift1) {
    const double x0 = m.L * m.rng.uniform(0, 0.25), y0 = m.L * m.rng.uniform(0, 0.25);
    const double s = m.L * m.rng.uniform(0.5, 0.75);
    return quad(m.at(x0, y0, z + lift0), m.at(x0 + s, y0, z + lift0), m.at(x0 + s, y0 + s, z + lift1),
                m.at(x0, y0 + s, z + lift1));
  };
  m.out.push_back(shifted(0, 0));
  m.out.push_back(flipped(shifted(0.5 * e, 0.5 * e)));
  m.out.push_back(shifted(2.5 * e, 2.5 * e));
  m.out.push_back(shifted(-1.5 * e, 1.5 * e));
}

void t_junctions(Motif& m) {
  const double L = m.L, z = L / 4, cut = L * m.rng.uniform(0.3, 0.7), mid = L * m.rng.uniform(0.3, 0.7);
  m.out.push_back(quad(m.at(0, 0, z), m.at(cut, 0, z), m.at(cut, L, z), m.at(0, L, z)));
  m.out.push_back(quad(m.at(cut, 0, z), m.at(L, 0, z), m.at(L, mid, z), m.at(cut, mid, z)));
  m.out.push_back(quad(m.at(cut, mid, z), m.at(L, mid, z), m.at(L, L, z), m.at(cut, L, z)));
  const double x0 = cut * m.rng.uniform(0.1, 0.4), x1 = cut * m.rng.uniform(0.6, 0.9);
  m.out.push_back(quad(m.at(x1, mid, z), m.at(x0, mid, z), m.at(x0, mid, z + L / 2), m.at(x1, mid, z + L / 2)));
}

void near_flat_fan(Motif& m) {
  const double L = m.L, z = L / 2, lift = m.eps * m.rng.uniform(0.5, 4.5);
  const Vec3 apex = m.at(L / 2, L / 2, z + lift);
  const Vec3 c[4] = {m.at(0, 0, z), m.at(L, 0, z), m.at(L, L, z), m.at(0, L, z)};
  for (int q = 0; q < 4; ++q) m.out.push_back(triangle(c[q], c[(q + 1) % 4], apex));
}

void near_touching(Motif& m) {
  const double L = m.L, z = L / 4, offsets[3] = {0.3, -0.6, 1.5};
  m.out.push_back(quad(m.at(0, 0, z), m.at(L, 0, z), m.at(L, L, z), m.at(0, L, z)));
  for (int q = 0; q < 3; ++q) {
    const double x = (q + 1) * L / 4, y = L * m.rng.uniform(0.1, 0.9), half = L / 10;
    m.out.push_back(triangle(m.at(x - half, y, z + L / 2), m.at(x, y, z + offsets[q] * m.eps),
                             m.at(x + half, y, z + L / 2)));
  }
}

void tiny(Motif& m) {
  const double legs[4] = {0.001, 0.5, 4, 50};
  for (double leg : legs) {
    const double s = leg * m.eps;
    const Vec3 p = m.at(m.L * m.rng.uniform(), m.L * m.rng.uniform(), m.L * m.rng.uniform());
    m.out.push_back(triangle(p, p + Vec3{s, 0, 0}, p + Vec3{0, s, 0}));
  }
}

void far_quads(double far, std::vector<Polygon>& out) {
  out.push_back(quad({-far, -far, -far}, {far, -far, -far}, {far, far, -far}, {-far, far, -far}));
  out.push_back(flipped(quad({-far, -far, far}, {far, -far, far}, {far, far, far}, {-far, far, far})));
}

std::size_t motif_count(std::size_t n) { return n >= 6 ? (n - 2) / 4 : 1; }

std::vector<Polygon> make(const ParamSet& p) {
  const double far = p.real("far");
  const double eps = Tolerance::for_extent(Box{{-far, -far, -far}, {far, far, far}}.diagonal()).plane_eps;
  const std::size_t motifs = motif_count(count_of(p));
  auto cells = static_cast<std::size_t>(std::cbrt(static_cast<double>(motifs)));
  while (cells * cells * cells < motifs) ++cells;
  const double h = 1.0 / static_cast<double>(cells);
  const std::uint64_t seed = seed_of(p);
  return generate_items(motifs + 1, [&](std::size_t item, std::vector<Polygon>& out) {
    if (item == 0) return far_quads(far, out);
    const std::size_t i = item - 1;
    const Vec3 lo{static_cast<double>(i % cells) * h, static_cast<double>((i / cells) % cells) * h,
                  static_cast<double>(i / (cells * cells)) * h};
    Motif m{lo + Vec3{kMargin, kMargin, kMargin} * h, (1 - 2 * kMargin) * h, eps, Rng(stream_seed(seed, i)), out};
    void (*const kinds[kKinds])(Motif&) = {slivers, near_coplanar, t_junctions, near_flat_fan, near_touching, tiny};
    kinds[i % kKinds](m);
  });
}

}  // namespace

GeneratorInfo near_degenerate_generator() {
  return {"near-degenerate",
          "slivers, near-coplanar overlaps, T-junctions, near-touching vertices and tiny polygons next to huge "
          "ones, all a few tolerances wide: the build must survive and count what it drops",
          "4 * max(1, floor((n - 2) / 4)) + 2 polygons: two huge quads and motifs of four",
          {n_param(1000, "largest number of polygons"), seed_param(),
           {"far", ParamSpec::Kind::Real,
            "half-side of the scene box set by the two huge quads; the tolerance is 1e-9 * 2 sqrt(3) * far", 1e4, 1,
            1e12, {}}},
          make,
          true};
}

}  // namespace bsp
