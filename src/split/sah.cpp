// `sah`: a kd-tree front end whose planes minimise the surface area heuristic [MacDonald1990;
// WaldHavran2006], the spatial subdivision of ray tracing, over solid trees' faces. While a node
// holds more than `leaf_faces` fragments, its plane is a free, axis-aligned one:
//  1. candidates: on each axis, the `bins` − 1 inner bounds of `bins` equal bins over the box of
//     the node's fragments [Wald2007: binned SAH];
//  2. cost of a candidate x: traversal_cost + (A(L)·n(L) + A(R)·n(R)) / A(B), where B is the
//     fragments' box, L and R its parts at x, A a box's surface area, and n the fragments
//     meeting each part (a fragment across x counts on both sides, as the faces of a kd-tree's
//     cells do);
//  3. the cheapest candidate wins (the lower axis, then the lower x, on ties) if it costs less
//     than the node as a leaf (m, one per fragment) and parts the fragments: at least one wholly
//     behind it and one wholly in front (farther than plane_eps), as `octree` requires.
// Otherwise, or at most `leaf_faces` fragments, the node goes to the autopartition heuristic named
// by `fallback`: the faces' own planes below the spatial levels, as in `octree`.
//
// Against `octree`: planes adapt to where the faces are (an empty region is cut off by one plane),
// but they depend on each operand's faces, so two operands of a set operation rarely share a plane
// and merging cuts one operand's cells by the other's planes.
// Cost per node: O(V) for the fragments' extents (V vertices), O(m + bins) per axis to count.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common/rng.h"
#include "split/fallbacks.h"
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
  int axis = -1;
  double x = 0;
  double cost = std::numeric_limits<double>::infinity();
};

class SahSplitter final : public Splitter {
 public:
  SahSplitter(const SahSettings& s, std::unique_ptr<Splitter> fallback) : s_(s), fallback_(std::move(fallback)) {}

  bool needs_cell() const override { return fallback_->needs_cell(); }
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<SahSplitter>(s_, fallback_->clone()); }

  SplitChoice choose(const SplitContext& ctx) override {
    if (ctx.ids.size() <= s_.leaf_faces) return fallback_->choose(ctx);
    measure_extents(ctx);
    const Candidate best = cheapest();
    const double leaf_cost = static_cast<double>(lo_.size());
    if (best.axis >= 0 && best.cost < leaf_cost && parts(best.axis, best.x, ctx.tol.plane_eps)) {
      const Vec3 n{best.axis == 0 ? 1.0 : 0.0, best.axis == 1 ? 1.0 : 0.0, best.axis == 2 ? 1.0 : 0.0};
      return SplitChoice::free_plane(Plane{n, -best.x});
    }
    return fallback_->choose(ctx);
  }

 private:
  void measure_extents(const SplitContext& ctx) {
    lo_.clear();
    hi_.clear();
    box_ = Box{};
    for (auto id : ctx.ids) {
      Box f;
      for (const Vec3& p : ctx.frags.points(id)) f.add(p);
      lo_.push_back(f.lo);
      hi_.push_back(f.hi);
      box_.add(f);
    }
  }

  // Binned counts: a fragment meets the parts below candidate k (k = 1 … bins − 1, at the bound
  // between bins k − 1 and k) when it starts in a bin below k, and the parts above when it ends in
  // bin k or above.
  Candidate cheapest() {
    Candidate best;
    const Vec3 size = box_.size();
    const double area = surface_area(size);
    if (!(area > 0)) return best;
    const std::size_t bins = s_.bins;
    for (int axis = 0; axis < 3; ++axis) {
      const double extent = size[axis];
      if (!(extent > 0)) continue;
      starts_.assign(bins, 0);
      ends_.assign(bins, 0);
      const double scale = static_cast<double>(bins) / extent;
      const auto bin = [&](double v) {
        const auto b = static_cast<std::int64_t>((v - box_.lo[axis]) * scale);
        return static_cast<std::size_t>(std::clamp<std::int64_t>(b, 0, static_cast<std::int64_t>(bins) - 1));
      };
      for (std::size_t i = 0; i < lo_.size(); ++i) {
        ++starts_[bin(lo_[i][axis])];
        ++ends_[bin(hi_[i][axis])];
      }
      std::size_t below = 0, above = lo_.size();  // fragments meeting the lower / upper part
      for (std::size_t k = 1; k < bins; ++k) {
        below += starts_[k - 1];
        above -= ends_[k - 1];
        const double x = box_.lo[axis] + extent * static_cast<double>(k) / static_cast<double>(bins);
        const Vec3 lower = with_axis(size, axis, x - box_.lo[axis]), upper = with_axis(size, axis, box_.hi[axis] - x);
        const double cost = s_.traversal_cost + (surface_area(lower) * static_cast<double>(below) +
                                                 surface_area(upper) * static_cast<double>(above)) /
                                                    area;
        if (cost < best.cost) best = {axis, x, cost};
      }
    }
    return best;
  }

  bool parts(int axis, double x, double eps) const {
    bool back = false, front = false;
    for (std::size_t i = 0; i < lo_.size() && !(back && front); ++i) {
      back |= hi_[i][axis] < x - eps;
      front |= lo_[i][axis] > x + eps;
    }
    return back && front;
  }

  SahSettings s_;
  std::unique_ptr<Splitter> fallback_;
  std::vector<Vec3> lo_, hi_;  // scratch, per fragment of the node
  std::vector<std::size_t> starts_, ends_;
  Box box_;
};

}  // namespace

HeuristicInfo sah_heuristic() {
  return {"sah",
          "spatial front end: axis-aligned planes minimising the surface area heuristic over binned candidates until a "
          "node holds few faces or a split costs more than a leaf, then the faces' own planes (kd-trees, MacDonald & "
          "Booth 1990; Wald & Havran 2006)",
          {{"leaf_faces", ParamSpec::Kind::Integer,
            "a node of more fragments than this may take an axis-aligned plane; fewer go to the fallback", 64, 1, 1e9, {}},
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
