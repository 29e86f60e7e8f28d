// `naylor`: greedy minimisation of Naylor's expected cost ("Constructing good partitioning trees",
// Graphics Interface 1993 [Naylor1993]): C(T) = 1 + P(T⁻)·C(T⁻) + P(T⁺)·C(T⁺), where P(child) is
// the chance that a query reaching the node goes on into that child. For point location (model =
// volume) it is the child cell's share of the parent cell's volume; for random lines or rays
// (model = area) it is the ratio of the child cell's surface area to the parent's, by Crofton's
// formula (the measure of lines meeting a convex body is proportional to its surface area). The
// children's costs are unknown while building, so each candidate is scored as
//   1 + P⁻·f(n⁻) + P⁺·f(n⁺),
// n± = fragments on that side with spanning ones on both, f a subtree-cost estimate (`estimate`).
// Scaling f by a constant cannot change which candidate wins (the 1 is common to all), so there is
// no scale parameter.
//
// Cells are exact: the scene box enlarged by `margin` (Box::enlarged, the root cell of the
// expected-cost metric, metrics/expected_cost.h, so at equal margins this greedily lowers what that
// metric measures), cut by the planes on the path from the root (ctx.cell_planes), each
// candidate's children measured in one pass over the cell's faces (ConvexPolytope::measure_split).
// The cells along the previous node's path are kept, and the build is depth-first, so a node's
// cell costs one clip of its parent's. Cost per node: O(m) + O(k·s) (s = sample, or m)
// classifications + k measures and one clip of a cell with O(depth) faces.
//
// 2D scenes (segments, geometry/segment2.h; the scene box has no height) are measured on prisms:
// the root cell's box is grown by `margin` in z as well, so a cell is its 2D cell times a height h.
// Volume ratios are then area ratios, and model=area takes the perimeter P = (S - 2V/h)/h from the
// prism's surface S and volume V: Crofton's formula in the plane measures the lines meeting a
// convex set by its perimeter.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/rng.h"
#include "geometry/polytope.h"
#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

namespace {

// When a cell has no measure (it can only collapse numerically, or the scene is flat and margin
// is 0) both children are taken as equally likely.
constexpr double kEvenProbability = 0.5;

enum class Model { Volume, Area };
enum class Estimate { NLogN, Linear, Log };

struct NaylorSettings {
  Model model;
  Estimate estimate;
  double margin;
  std::uint64_t candidates;
  std::uint64_t sample;

  static NaylorSettings from(const ParamSet& p) {
    const std::string& e = p.choice("estimate");
    return {p.choice("model") == "volume" ? Model::Volume : Model::Area,
            e == "nlogn" ? Estimate::NLogN : (e == "linear" ? Estimate::Linear : Estimate::Log), p.real("margin"),
            static_cast<std::uint64_t>(p.integer("candidates")), static_cast<std::uint64_t>(p.integer("sample"))};
  }
};

class NaylorSplitter final : public Splitter {
 public:
  NaylorSplitter(const NaylorSettings& s, std::uint64_t seed) : s_(s), seed_(seed) {}

  bool needs_cell() const override { return true; }
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<NaylorSplitter>(*this); }

  SplitChoice choose(const SplitContext& ctx) override {
    update_cell(ctx);
    const double whole = measure(cell().volume(), s_.model == Model::Area ? cell().surface_area() : 0.0);
    Rng rng(stream_seed(seed_, ctx.node_key));
    const auto candidates = candidate_fragments(ctx, s_.candidates, rng, scratch_);
    const SideCounter count(ctx, s_.sample, rng, scratch_);
    return SplitChoice::of_fragment(argmin_candidate(count, candidates, [&](std::uint32_t id, const SideCounts& c) {
      const auto [p_front, p_back] = probabilities(ctx, ctx.planes[ctx.frags.plane(id)], whole);
      return 1.0 + p_back * estimate(count.scale() * (c.back + c.spanning)) +
             p_front * estimate(count.scale() * (c.front + c.spanning));
    }));
  }

 private:
  // The cell's measure from its volume and surface: those in 3D, its 2D area or perimeter in 2D
  // (path_.prism_height > 0).
  double measure(double volume, double surface) const {
    if (s_.model == Model::Volume) return volume;
    if (path_.prism_height == 0) return surface;
    return (surface - 2 * volume / path_.prism_height) / path_.prism_height;
  }

  // P⁺ and P⁻ of a candidate plane, from one pass over the cell's faces (no child polytope is built).
  std::pair<double, double> probabilities(const SplitContext& ctx, const Plane& p, double whole) const {
    if (!(whole > 0)) return {kEvenProbability, kEvenProbability};
    const ConvexPolytope::SplitMeasure m = cell().measure_split(
        p, ctx.tol.plane_eps,
        s_.model == Model::Volume ? ConvexPolytope::Measures::Volumes : ConvexPolytope::Measures::VolumesAndAreas);
    return {measure(m.front_volume, m.front_area) / whole, measure(m.back_volume, m.back_area) / whole};
  }

  // f(n), the cost charged for a child holding n fragments. Naylor's recursion wants the children's
  // expected costs, which a greedy choice cannot know yet; these stand in for them:
  //  nlogn = n·log2(n+1): a subtree over n fragments has about n nodes at depths up to ~log2 n, and
  //    the superlinear growth charges a plane that leaves many fragments in a likely child more
  //    than their number alone would;
  //  linear = n: testing every fragment of the cell, what the surface area heuristic of ray-tracing
  //    kd-trees charges (MacDonald and Booth 1990);
  //  log = log2(n+1): the depth of a balanced subtree, the path a point query walks.
  double estimate(double x) const {
    switch (s_.estimate) {
      case Estimate::NLogN: return x * std::log2(x + 1);
      case Estimate::Linear: return x;
      case Estimate::Log: return std::log2(x + 1);
    }
    return x;
  }

  // Brings cell() to the node's cell. path_ holds the cells along the previous node's path, so a
  // node clips only the planes past the path it shares with the previous one: one clip for a child
  // of the previous node, and one for the back child of an ancestor that the depth-first build
  // comes back to, instead of O(depth) from the box. Cells past the path keep their memory for the
  // next node that goes as deep.
  void update_cell(const SplitContext& ctx) {
    const auto& want = ctx.cell_planes;
    std::vector<ConvexPolytope>& cells = path_.cells;
    std::size_t shared = 0;
    while (shared < want.size() && shared < path_.planes.size() && want[shared] == path_.planes[shared]) ++shared;
    if (cells.empty()) {
      const Box root = ctx.scene_box.enlarged(s_.margin);
      if (ctx.scene_box.hi.z == ctx.scene_box.lo.z) path_.prism_height = root.hi.z - root.lo.z;
      cells.push_back(ConvexPolytope::box(root));
    }
    if (cells.size() < want.size() + 1) cells.resize(want.size() + 1);
    for (std::size_t i = shared; i < want.size(); ++i)
      cells[i].clip_into(ctx.planes[want[i]], ctx.tol.plane_eps, cells[i + 1]);
    path_.planes.assign(want.begin(), want.end());
  }

  // The node's cell, once update_cell has run.
  const ConvexPolytope& cell() const { return path_.cells[path_.planes.size()]; }

  // The cells along the previous node's path: scratch, not state. A copy (a task's clone of the
  // splitter) starts empty: its builder numbers planes in a pool of its own, where the indices in
  // `planes` would name other planes and a shared prefix would be a coincidence of numbers.
  struct CellPath {
    CellPath() = default;
    CellPath(const CellPath&) {}
    CellPath& operator=(const CellPath&) { return *this; }

    std::vector<std::uint32_t> planes;  // the pooled planes the previous node's cell was cut by
    std::vector<ConvexPolytope> cells;  // cells[i]: the root cell cut by planes[0, i), i <= planes.size()
    double prism_height = 0;            // 2D scenes: the height of the prisms cells are measured on
  };

  NaylorSettings s_;
  std::uint64_t seed_;
  CandidateScratch scratch_;
  CellPath path_;
};

}  // namespace

HeuristicInfo naylor_heuristic() {
  return {"naylor",
          "Naylor 1993 expected cost: min 1 + P-*f(n-) + P+*f(n+), P from exact cell volume or surface area",
          {{"model", ParamSpec::Kind::Choice,
            "probability of entering a child: volume (point location) or area (random lines, Crofton); in 2D "
            "scenes the cell's area and perimeter",
            0, 0, 0,
            {"volume", "area"}},
           {"estimate", ParamSpec::Kind::Choice,
            "subtree cost estimate f(n): nlogn = n*log2(n+1), linear = n (SAH-like), log = log2(n+1) (balanced depth)",
            0, 0, 0, {"nlogn", "linear", "log"}},
           {"margin", ParamSpec::Kind::Real,
            "the root cell is the scene box grown by this times max(diagonal, 1) on every side (Box::enlarged, "
            "the root cell of the expected-cost metric)",
            0.01, 0.0, 10.0, {}},
           candidates_param(16, "; each also costs one cell clip (two for model=area)"), sample_param(0)},
          true,
          [](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<NaylorSplitter>(NaylorSettings::from(p), stream_seed(seed, 0x9a71));
          }};
}

}  // namespace bsp
