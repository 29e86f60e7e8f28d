// `sah`: a kd-tree front end whose planes minimise the surface area heuristic [MacDonald1990;
// WaldHavran2006], the spatial subdivision of ray tracing, over solid trees' faces. While a node
// holds more than `leaf_faces` fragments, its plane is a free, axis-aligned one:
//  1. candidates: on each axis, the `bins` − 1 inner bounds of `bins` equal bins over the box of
//     the node's fragments [Wald2007: binned SAH];
//  2. cost of a candidate x: traversal_cost + (A(L)·n(L) + A(R)·n(R)) / A(B), where B is the
//     fragments' box, L and R its parts at x, A a box's surface area, and n the fragments
//     meeting each part (a fragment across x counts on both sides, as the faces of a kd-tree's
//     cells do);
//  3. the cheapest candidate that parts the fragments (at least one wholly behind it and one
//     wholly in front, farther than plane_eps, as `octree` requires) wins, the lower axis and then
//     the lower x on ties, if it costs less than the node as a leaf (m, one per fragment).
// Otherwise, or at most `leaf_faces` fragments, the node goes to the autopartition heuristic named
// by `fallback`: the faces' own planes below the spatial levels, as in `octree`.
//
// Against `octree`: planes adapt to where the faces are (an empty region is cut off by one plane),
// but they depend on each operand's faces, so two operands of a set operation rarely share a plane
// and merging cuts one operand's cells by the other's planes.
// Cost per node: O(V) for the fragments' extents (V vertices), O(m + bins) per axis to count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include "common/rng.h"
#include "split/fallbacks.h"
#include "split/fragment_extents.h"
#include "split/registry.h"

namespace bsp {

namespace {

struct SahSettings {
  std::size_t leaf_faces;
  std::size_t bins;
  double traversal_cost;  // of one node, in units of one fragment's test
};

double surface_area(const Vec3& size) { return 2 * (size.x * size.y + size.y * size.z + size.z * size.x); }

Vec3 with_axis(Vec3 v, int axis, double value) {
  (axis == 0 ? v.x : (axis == 1 ? v.y : v.z)) = value;
  return v;
}

struct Candidate {
  double cost;
  int axis;
  double x;
  bool operator<(const Candidate& o) const { return std::tie(cost, axis, x) < std::tie(o.cost, o.axis, o.x); }
};

class SahSplitter final : public Splitter {
 public:
  SahSplitter(const SahSettings& s, std::unique_ptr<Splitter> fallback) : s_(s), fallback_(std::move(fallback)) {}

  bool needs_cell() const override { return fallback_->needs_cell(); }
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<SahSplitter>(s_, fallback_->clone()); }

  SplitChoice choose(const SplitContext& ctx) override {
    if (ctx.ids.size() <= s_.leaf_faces) return fallback_->choose(ctx);
    extents_.measure(ctx);
    cost_candidates();
    std::sort(candidates_.begin(), candidates_.end());
    const double leaf_cost = static_cast<double>(extents_.size());
    for (const Candidate& c : candidates_) {
      if (!(c.cost < leaf_cost)) break;
      if (!extents_.parts(c.axis, c.x, ctx.tol.plane_eps)) continue;
      const Vec3 n{c.axis == 0 ? 1.0 : 0.0, c.axis == 1 ? 1.0 : 0.0, c.axis == 2 ? 1.0 : 0.0};
      return SplitChoice::free_plane(Plane{n, -c.x});
    }
    return fallback_->choose(ctx);
  }

 private:
  // Binned counts: a fragment meets the part below candidate k (k = 1 … bins − 1, at the bound
  // between bins k − 1 and k) when it starts in a bin below k, and the part above when it ends in
  // bin k or above. A start on a bound is in the bin above it and an end on a bound in the bin
  // below, so a fragment ending on candidate k counts below it only, one starting there above it
  // only, and a face lying in it on neither side (the build puts it on the node).
  void cost_candidates() {
    candidates_.clear();
    const Box& box = extents_.box();
    const Vec3 size = box.size();
    const double area = surface_area(size);
    if (!(area > 0)) return;
    const std::size_t bins = s_.bins;
    for (int axis = 0; axis < 3; ++axis) {
      const double extent = size[axis];
      if (!(extent > 0)) continue;
      starts_.assign(bins, 0);
      ends_.assign(bins, 0);
      const double scale = static_cast<double>(bins) / extent;
      const auto clamped = [&](double b) {
        return static_cast<std::size_t>(std::clamp(b, 0.0, static_cast<double>(bins) - 1));
      };
      for (std::size_t i = 0; i < extents_.size(); ++i) {
        ++starts_[clamped(std::floor((extents_.lo(i)[axis] - box.lo[axis]) * scale))];
        ++ends_[clamped(std::ceil((extents_.hi(i)[axis] - box.lo[axis]) * scale) - 1)];
      }
      std::size_t below = 0, above = extents_.size();  // fragments meeting the lower / upper part
      for (std::size_t k = 1; k < bins; ++k) {
        below += starts_[k - 1];
        above -= ends_[k - 1];
        const double x = box.lo[axis] + extent * static_cast<double>(k) / static_cast<double>(bins);
        const Vec3 lower = with_axis(size, axis, x - box.lo[axis]), upper = with_axis(size, axis, box.hi[axis] - x);
        const double cost = s_.traversal_cost + (surface_area(lower) * static_cast<double>(below) +
                                                 surface_area(upper) * static_cast<double>(above)) /
                                                    area;
        candidates_.push_back({cost, axis, x});
      }
    }
  }

  SahSettings s_;
  std::unique_ptr<Splitter> fallback_;
  FragmentExtents extents_;  // scratch, of the node being chosen for
  std::vector<std::size_t> starts_, ends_;
  std::vector<Candidate> candidates_;
};

}  // namespace

// The defaults: octree's leaf_faces, so the two front ends differ in where they cut and not in how
// deep; 16 bins per axis as [Wald2007] found enough; a node test as dear as a face test.
HeuristicInfo sah_heuristic() {
  return {"sah",
          "spatial front end: axis-aligned planes minimising the surface area heuristic over binned candidates until a "
          "node holds few faces or a split costs more than a leaf, then the faces' own planes (kd-trees, MacDonald & "
          "Booth 1990; Wald & Havran 2006)",
          {{"leaf_faces", ParamSpec::Kind::Integer,
            "a node of more fragments than this may take an axis-aligned plane; at most this many go to the fallback", 64, 1, 1e9, {}},
           {"bins", ParamSpec::Kind::Integer, "equal bins per axis; their inner bounds are the candidate planes", 16, 2,
            1024, {}},
           {"traversal_cost", ParamSpec::Kind::Real, "cost of a node against one fragment's test, in the SAH", 1, 0, 1e6,
            {}},
           {"fallback", ParamSpec::Kind::Choice, "autopartition heuristic (default parameters) below leaf_faces", 0, 0,
            0, autopartition_fallbacks("first")}},
          false,
          [](const ParamSet& p, std::uint64_t seed) {
            const SahSettings s{static_cast<std::size_t>(p.integer("leaf_faces")),
                                static_cast<std::size_t>(p.integer("bins")), p.real("traversal_cost")};
            return std::make_unique<SahSplitter>(s, make_splitter(p.choice("fallback"), {}, stream_seed(seed, 0x5a4)));
          }};
}

}  // namespace bsp
