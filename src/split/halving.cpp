// `halving`: Torres' halving planes ([Torres1990]; [Chrysanthou §8]: "planes chosen to be parallel
// to as many object polygons as possible to minimise splits and positioned so as to have an almost
// equal number of the polygons on each side"). A free plane, through no polygon:
//  1. orientation: the node's fragments' planes grouped by normal direction, both facings alike,
//     within `angle_tolerance` (parallel_groups.h); the most populated group wins, the earliest
//     on ties, and its first normal is the plane's normal u;
//  2. offset: each fragment projects onto u as an interval [lo, hi]. The places worth trying are
//     midway between consecutive distinct interval ends (ends closer than 2·plane_eps count as
//     one), where the plane passes through no fragment. A place is usable when it leaves at least
//     one whole fragment on each side. Usable places whose imbalance |front − back| is within
//     balance_slack·m of the best one are "near the median"; among them a gap (no fragment
//     crossing) is preferred, the widest; failing a gap, the one cutting fewest fragments, then
//     the better balance, then the lower place.
// When no place is usable (all fragments coplanar with u, or every place leaves a side with
// nothing whole on it), the node goes to the autopartition heuristic named by `fallback`. Each
// accepted plane leaves at most m − 1 fragments on either side, so the recursion ends.
//
// Cost per node: O(m) expected to group orientations, O(V + m log m) to place (V vertices).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "common/rng.h"
#include "split/parallel_groups.h"
#include "split/fallbacks.h"
#include "split/registry.h"

namespace bsp {

namespace {

struct HalvingSettings {
  double angle;          // radians
  double balance_slack;  // fraction of the node's fragments
};

// One place for the plane along u and what it does to the node's fragments.
struct Place {
  double x = 0;      // the plane is u·p = x
  double width = 0;  // distance between the interval ends it lies between
  std::uint32_t back = 0, front = 0, spanning = 0;

  std::uint32_t imbalance() const { return front > back ? front - back : back - front; }
};

Vec3 most_populated_orientation(const SplitContext& ctx, double angle) {
  std::vector<Vec3> normals;
  normals.reserve(ctx.ids.size());
  for (auto id : ctx.ids) normals.push_back(ctx.planes[ctx.frags.plane(id)].n);
  const ParallelGroups g = group_parallel(normals, angle);
  const auto best = std::max_element(g.size.begin(), g.size.end()) - g.size.begin();
  return g.representative[static_cast<std::size_t>(best)];
}

// The fragments' extents along u, each list sorted on its own.
struct Extents {
  std::vector<double> lo, hi;
};

Extents extents_along(const SplitContext& ctx, const Vec3& u) {
  Extents e;
  for (auto id : ctx.ids) {
    double a = std::numeric_limits<double>::infinity(), b = -a;
    for (const Vec3& p : ctx.frags.points(id)) {
      const double t = dot(u, p);
      a = std::min(a, t);
      b = std::max(b, t);
    }
    e.lo.push_back(a);
    e.hi.push_back(b);
  }
  std::sort(e.lo.begin(), e.lo.end());
  std::sort(e.hi.begin(), e.hi.end());
  return e;
}

// Every usable place along u: midway between consecutive distinct interval ends. A fragment is
// behind the plane when its top end is, in front when its bottom end is, and crosses it otherwise.
std::vector<Place> usable_places(const SplitContext& ctx, const Vec3& u) {
  const double eps = ctx.tol.plane_eps;
  const Extents e = extents_along(ctx, u);
  std::vector<double> ends(e.lo);
  ends.insert(ends.end(), e.hi.begin(), e.hi.end());
  std::sort(ends.begin(), ends.end());
  const auto m = static_cast<std::uint32_t>(e.lo.size());
  std::vector<Place> places;
  for (std::size_t i = 1; i < ends.size(); ++i) {
    if (ends[i] - ends[i - 1] <= 2 * eps) continue;  // midway would be within eps of a fragment
    Place p;
    p.x = 0.5 * (ends[i - 1] + ends[i]);
    p.width = ends[i] - ends[i - 1];
    p.back = static_cast<std::uint32_t>(std::upper_bound(e.hi.begin(), e.hi.end(), p.x) - e.hi.begin());
    p.front = m - static_cast<std::uint32_t>(std::lower_bound(e.lo.begin(), e.lo.end(), p.x) - e.lo.begin());
    p.spanning = m - p.back - p.front;
    if (p.back > 0 && p.front > 0) places.push_back(p);
  }
  return places;
}

// The widest gap near the median, else the place near the median cutting fewest.
std::optional<Place> best_place(const std::vector<Place>& places, double slack, std::size_t m) {
  if (places.empty()) return std::nullopt;
  std::uint32_t best_imbalance = places.front().imbalance();
  for (const auto& p : places) best_imbalance = std::min(best_imbalance, p.imbalance());
  const double window = best_imbalance + slack * static_cast<double>(m);
  const Place* gap = nullptr;
  const Place* cut = nullptr;
  for (const auto& p : places) {
    if (p.imbalance() > window) continue;
    if (p.spanning == 0 && (!gap || p.width > gap->width || (p.width == gap->width && p.imbalance() < gap->imbalance())))
      gap = &p;
    if (!cut || p.spanning < cut->spanning || (p.spanning == cut->spanning && p.imbalance() < cut->imbalance()))
      cut = &p;
  }
  return gap ? *gap : *cut;
}

class HalvingSplitter final : public Splitter {
 public:
  HalvingSplitter(const HalvingSettings& s, std::unique_ptr<Splitter> fallback)
      : s_(s), fallback_(std::move(fallback)) {}

  bool needs_cell() const override { return fallback_->needs_cell(); }
  std::unique_ptr<Splitter> clone() const override {
    return std::make_unique<HalvingSplitter>(s_, fallback_->clone());
  }

  SplitChoice choose(const SplitContext& ctx) override {
    const Vec3 u = most_populated_orientation(ctx, s_.angle);
    if (const auto place = best_place(usable_places(ctx, u), s_.balance_slack, ctx.ids.size()))
      return SplitChoice::free_plane(Plane{u, -place->x});
    return fallback_->choose(ctx);
  }

 private:
  HalvingSettings s_;
  std::unique_ptr<Splitter> fallback_;
};

constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;


}  // namespace

HeuristicInfo halving_heuristic() {
  return {"halving",
          "Torres' halving planes: free plane parallel to the most polygons, in the widest gap near the median "
          "(Torres 1990)",
          {{"angle_tolerance", ParamSpec::Kind::Real,
            "degrees within which two polygon planes (either facing) count as parallel", 0.01, 1e-9, 10.0, {}},
           {"balance_slack", ParamSpec::Kind::Real,
            "places whose |front-back| is within this fraction of the node's fragments of the best count as near "
            "the median",
            0.1, 0.0, 1.0, {}},
           {"fallback", ParamSpec::Kind::Choice,
            "autopartition heuristic (default parameters) for nodes no halving plane separates", 0, 0, 0,
            autopartition_fallbacks("balanced")}},
          false,
          [](const ParamSet& p, std::uint64_t seed) {
            const HalvingSettings s{p.real("angle_tolerance") * kRadiansPerDegree, p.real("balance_slack")};
            return std::make_unique<HalvingSplitter>(s, make_splitter(p.choice("fallback"), {}, stream_seed(seed, 0x4a1f)));
          }};
}

}  // namespace bsp
