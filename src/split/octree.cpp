// `octree`: a spatial front end after the octree-embedded BSPs of [NehringWirxel2021], whose octree
// keeps every boolean local and bounds the size of the BSPs inside its cells. While a node holds
// more than `leaf_faces` fragments its plane is a free, axis-aligned one:
//  1. axis: the longest extent of the box of the node's fragments (x, y, z on ties); failing it,
//     the next longest;
//  2. offset: the coarsest point of the dyadic lattice k·2^e (the largest e) inside the middle half
//     of the fragments' extent along that axis; 0 when the middle half holds 0. The plane is
//     usable when at least one fragment lies wholly behind it and one wholly in front (farther
//     than plane_eps), as `halving` requires.
// A node of at most `leaf_faces` fragments, or one no axis parts, goes to the autopartition
// heuristic named by `fallback`: its faces' own planes, so the tree's lower levels are small
// autopartitions of the faces a spatial cell holds, not one chain as deep as the solid has faces.
//
// Why a lattice and not the cell's midpoint: the planes depend on no scene box, so two operands of a
// set operation, and every step of a CSG program, cut space on the same planes wherever their
// extents are alike; merging then meets coplanar nodes, whose partition is the node's own children
// (nothing is cut). Lattice coordinates are also exact in the exact kernel's grid.
//
// Each accepted plane leaves a whole fragment on each side, so each child holds at most m − 1 of the
// node's m fragments (a spanning one goes to both as pieces) and the recursion ends.
// Cost per node: O(V) for the fragments' extents (V vertices), O(m) to count each axis's sides.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/rng.h"
#include "split/fallbacks.h"
#include "split/fragment_extents.h"
#include "split/registry.h"

namespace bsp {

namespace {

// The coarsest lattice point k·2^e in [a, b], a < b. [a, b] holds a multiple of 2^e for
// 2^e <= b - a (e is lowered while the rounded difference says otherwise); e rises while it holds a
// multiple of 2^(e+1) (at most log2(max(|a|, |b|) / (b - a)) steps, as 0 is outside). Two
// consecutive multiples of 2^e include one of 2^(e+1), so the last e has exactly one.
double coarsest_lattice_point(double a, double b) {
  if (a <= 0 && b >= 0) return 0;
  const auto holds_multiple = [&](int e) { return std::ceil(std::ldexp(a, -e)) <= std::floor(std::ldexp(b, -e)); };
  int e = std::ilogb(b - a);
  while (!holds_multiple(e)) --e;
  while (e < std::numeric_limits<double>::max_exponent && holds_multiple(e + 1)) ++e;
  return std::ldexp(std::ceil(std::ldexp(a, -e)), e);
}

// The plane lies in the middle half of the fragments' extent: this much of the extent is kept
// clear at each end, so that neither side is a sliver of the node.
constexpr double kEndMargin = 0.25;

struct OctreeSettings {
  std::size_t leaf_faces;
};

class OctreeSplitter final : public Splitter {
 public:
  OctreeSplitter(const OctreeSettings& s, std::unique_ptr<Splitter> fallback) : s_(s), fallback_(std::move(fallback)) {}

  bool needs_cell() const override { return fallback_->needs_cell(); }
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<OctreeSplitter>(s_, fallback_->clone()); }

  SplitChoice choose(const SplitContext& ctx) override {
    if (ctx.ids.size() <= s_.leaf_faces) return fallback_->choose(ctx);
    extents_.measure(ctx);
    const Box& box = extents_.box();
    for (int axis : axes_by_extent()) {
      const double a = box.lo[axis] + kEndMargin * (box.hi[axis] - box.lo[axis]);
      const double b = box.hi[axis] - kEndMargin * (box.hi[axis] - box.lo[axis]);
      if (!(a < b)) break;  // the fragments have no extent along this axis, nor any shorter one
      const double x = coarsest_lattice_point(a, b);
      if (extents_.parts(axis, x, ctx.tol.plane_eps)) {
        const Vec3 n{axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
        return SplitChoice::free_plane(Plane{n, -x});
      }
    }
    return fallback_->choose(ctx);
  }

 private:
  std::array<int, 3> axes_by_extent() const {
    std::array<int, 3> axes{0, 1, 2};
    const Vec3 size = extents_.box().size();
    std::stable_sort(axes.begin(), axes.end(), [&](int i, int j) { return size[i] > size[j]; });
    return axes;
  }

  OctreeSettings s_;
  std::unique_ptr<Splitter> fallback_;
  FragmentExtents extents_;  // scratch, of the node being chosen for
};


}  // namespace

// The defaults, first below 64 faces, gave the fastest union of two spheres of 10^4 and 10^5 faces,
// builds and merge included, of leaf_faces 4 to 512 with first and 4 to 64 with crystal
// (docs/solids.md).
HeuristicInfo octree_heuristic() {
  return {"octree",
          "spatial front end: axis-aligned planes on a dyadic lattice until a node holds few faces, then the faces' "
          "own planes (octree-embedded BSPs, Nehring-Wirxel et al. 2021)",
          {{"leaf_faces", ParamSpec::Kind::Integer,
            "a node of more fragments than this takes an axis-aligned plane; fewer go to the fallback", 64, 1, 1e9, {}},
           {"fallback", ParamSpec::Kind::Choice, "autopartition heuristic (default parameters) below leaf_faces", 0, 0,
            0, autopartition_fallbacks("first")}},
          false,
          [](const ParamSet& p, std::uint64_t seed) {
            const OctreeSettings s{static_cast<std::size_t>(p.integer("leaf_faces"))};
            return std::make_unique<OctreeSplitter>(s, make_splitter(p.choice("fallback"), {}, stream_seed(seed, 0x0c7e)));
          }};
}

}  // namespace bsp
