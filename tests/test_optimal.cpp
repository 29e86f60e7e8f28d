// Optimal autopartitions (search/optimal.h): the branch and bound against brute-force enumeration
// of every autopartition for inputs of at most 6 fragments, in 3D and 2D, for every objective and
// shape; the certificate tree measured by the metrics; no heuristic's autopartition below the
// proved optimum; and budgets that stop the search with an interval holding the optimum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "catalog.h"
#include "common/errors.h"
#include "experiments/optimal/optimal.h"
#include "geometry/polytope.h"
#include "geometry/segment2.h"
#include "search/optimal.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/build_input.h"
#include "validate/tree_invariants.h"

using namespace bsp;

namespace {

// A fragment of the brute force: its polygon and its pooled supporting plane.
struct Piece {
  Polygon poly;
  std::uint32_t plane;
};

// Every autopartition enumerated, no memo and no bounds: the least value over all trees of
// `pieces` in `cell`, by the same partition rules as the build loop (tree/build.cpp).
class BruteForce {
 public:
  BruteForce(OptimalObjective objective, Shape shape, const TreeDraft& draft, bool planar, const ConvexPolytope& root)
      : objective_(objective), shape_(shape), planes_(draft.planes), eps_(draft.tol.plane_eps), planar_(planar) {
    std::tie(root_volume_, root_area_) = measures(root);
  }

  // With `memo`, each (fragments, cell) is solved once: the same enumeration, without the
  // branch and bound's bounds, reaching inputs where subproblems recur.
  void use_memo() { memo_on_ = true; }

  double best(const std::vector<Piece>& pieces, const ConvexPolytope& cell) const {
    std::vector<double> key;
    if (memo_on_) {
      std::vector<std::vector<double>> frags;
      for (const Piece& f : pieces) {
        frags.push_back({static_cast<double>(f.poly.source), static_cast<double>(f.plane)});
        for (const Vertex& v : f.poly.verts) frags.back().insert(frags.back().end(), {v.p.x, v.p.y, v.p.z});
      }
      std::sort(frags.begin(), frags.end());
      for (const auto& f : frags) {
        key.push_back(-1e300);  // a separator no coordinate takes
        key.insert(key.end(), f.begin(), f.end());
      }
      if (objective_ != OptimalObjective::Fragments)
        for (std::size_t i = 0; i < cell.face_count(); ++i)
          for (const Vec3& v : cell.face(i)) key.insert(key.end(), {v.x, v.y, v.z});
      if (auto it = memo_.find(key); it != memo_.end()) return it->second;
    }
    const double value = enumerate(pieces, cell);
    if (memo_on_) memo_.emplace(std::move(key), value);
    return value;
  }

 private:
  double enumerate(const std::vector<Piece>& pieces, const ConvexPolytope& cell) const {
    const auto [volume, area] = measures(cell);
    if (is_leaf(pieces)) return objective_ == OptimalObjective::Fragments ? pieces.size()
                                : objective_ == OptimalObjective::EPoint  ? 0.0
                                                                          : area / root_area_;
    double least = std::numeric_limits<double>::infinity();
    std::vector<std::uint32_t> tried;
    for (const Piece& candidate : pieces) {
      const std::uint32_t key = shape_ == Shape::Leafy ? candidate.plane : candidate.plane >> 1;
      if (std::find(tried.begin(), tried.end(), key) != tried.end()) continue;
      tried.push_back(key);
      const Plane p = planes_[candidate.plane];
      std::vector<Piece> front, back;
      std::size_t coplanar = 0;
      for (const Piece& f : pieces) {
        switch (classify(f.poly, p, eps_)) {
          case Side::Front: front.push_back(f); break;
          case Side::Back: back.push_back(f); break;
          case Side::Coplanar:
            if (shape_ != Shape::Leafy) ++coplanar;
            else (dot(planes_[f.plane].n, p.n) > 0 ? front : back).push_back(f);
            break;
          case Side::Spanning: {
            Polygon a, b;
            const SplitKept kept = f.poly.verts.size() == 2 ? split_segment_into(f.poly, p, eps_, a, b)
                                                            : split_into(f.poly, p, eps_, a, b);
            if (kept.front) front.push_back({a, f.plane});
            if (kept.back) back.push_back({b, f.plane});
            break;
          }
        }
      }
      if (shape_ == Shape::Leafy && (front.empty() || back.empty())) continue;
      double value = objective_ == OptimalObjective::Fragments ? coplanar
                     : objective_ == OptimalObjective::EPoint  ? volume / root_volume_
                                                               : area / root_area_;
      if (!front.empty()) value += best(front, cell.clipped(p, eps_));
      if (!back.empty()) value += best(back, cell.clipped(p.flipped(), eps_));
      least = std::min(least, value);
    }
    return least;
  }

  std::pair<double, double> measures(const ConvexPolytope& c) const {
    if (!planar_) return {c.volume(), c.surface_area()};
    const auto s = c.top_section();
    return {s.area, s.perimeter};
  }
  // Coarse: every fragment in front of or on every other's plane. Leafy: that, with coplanar
  // fragments facing the same way.
  bool is_leaf(const std::vector<Piece>& pieces) const {
    if (shape_ == Shape::Strict) return false;
    for (const Piece& a : pieces)
      for (const Piece& b : pieces) {
        const Side side = classify(b.poly, planes_[a.plane], eps_);
        if (side == Side::Back || side == Side::Spanning) return false;
        if (shape_ == Shape::Leafy && side == Side::Coplanar && dot(planes_[a.plane].n, planes_[b.plane].n) <= 0) return false;
      }
    return true;
  }

  OptimalObjective objective_;
  Shape shape_;
  const PlanePool& planes_;
  double eps_;
  bool planar_;
  double root_volume_ = 1, root_area_ = 1;
  bool memo_on_ = false;
  mutable std::map<std::vector<double>, double> memo_;
};

double brute_force(const std::vector<Polygon>& input, OptimalObjective objective, Shape shape, double margin,
                   bool memo = false) {
  TreeDraft draft;
  const std::vector<std::uint32_t> ids = load_input(input, draft);
  std::vector<Piece> pieces;
  for (auto id : ids) {
    Polygon p;
    draft.store.view(id).copy_to(p);
    pieces.push_back({p, draft.store.plane(id)});
  }
  const ConvexPolytope root = ConvexPolytope::box(draft.bounds.enlarged(margin));
  BruteForce b(objective, shape, draft, all_segments(input), root);
  if (memo) b.use_memo();
  return b.best(pieces, root);
}

// Small scenes of the kinds the solver serves: triangle soups that cut each other, cyclic overlaps
// no order resolves, and disjoint 2D segments long enough to cross each other's lines.
std::vector<std::pair<std::string, std::vector<Polygon>>> small_scenes(std::uint32_t n) {
  std::vector<std::pair<std::string, std::vector<Polygon>>> out;
  for (int seed = 1; seed <= 4; ++seed) {
    const std::string s = std::to_string(seed);
    out.push_back({"random-triangles seed " + s,
                   make_scene("random-triangles", {{"n", std::to_string(n)}, {"seed", s}, {"size", "0.5"}}).polygons});
    out.push_back({"random-segments seed " + s,
                   make_scene("random-segments", {{"n", std::to_string(n)}, {"seed", s}}).polygons});
  }
  out.push_back({"cyclic-overlap", make_scene("cyclic-overlap", {{"n", "6"}}).polygons});
  return out;
}

bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)); }

}  // namespace

TEST(Optimal, MatchesBruteForceOnEverySmallScene) {
  for (std::uint32_t n : {3u, 5u, 6u})
    for (const auto& [name, input] : small_scenes(n))
      for (auto objective : {OptimalObjective::Fragments, OptimalObjective::EPoint, OptimalObjective::ELine})
        for (auto shape : {Shape::Strict, Shape::Coarse, Shape::Leafy}) {
          OptimalSettings s;
          s.objective = objective;
          s.shape = shape;
          const OptimalResult r = solve_optimal(input, s);
          const double truth = brute_force(input, objective, shape, s.cell_margin);
          const std::string what = name + " n=" + std::to_string(n) + " " + objective_name(objective) + " " + shape_name(shape);
          ASSERT_TRUE(r.optimal()) << what;
          EXPECT_TRUE(close(r.upper, truth)) << what << ": solver " << r.upper << ", brute force " << truth;
          EXPECT_TRUE(close(experiments::objective_value(r.tree, input, objective, s.cell_margin), truth))
              << what << ": the certificate's measured value differs";
          EXPECT_EQ(check_tree_invariants(r.tree, input).violations, 0u) << what;
        }
}

// A triangle a few tolerances thin that a plane along its long edge cuts into two slivers, both
// dropped: the fragment vanishes, so counting every fragment as at least one stored piece would
// bound the optimum above its value. The search must still match the enumeration.
TEST(Optimal, AFragmentBothOfWhosePartsAreDroppedDoesNotBreakTheBound) {
  std::vector<Polygon> input;
  const auto add = [&](Vec3 a, Vec3 b, Vec3 c) {
    input.push_back(Polygon{{Vertex{a}, Vertex{b}, Vertex{c}}, static_cast<std::uint32_t>(input.size())});
  };
  // Cutters in the plane y = 0.5, away from the thin triangle in z; a bystander in x = 2.
  const double y = 0.5;
  for (double z : {-1.0, 2.0}) add({0, y, z}, {1, y, z}, {0, y, z + 0.5});
  add({2, 0, 0}, {2, 1, 0}, {2, 0, 1});
  Box box;
  for (const Polygon& p : input)
    for (const Vertex& v : p.verts) box.add(v.p);
  const double eps = kPlaneEpsRelative * box.diagonal();
  // The thin triangle: its long edge at y - 1.125 eps, its apex at y + 1.375 eps (2.5 eps high).
  add({0.1, y - 1.125 * eps, 0.5}, {0.9, y - 1.125 * eps, 0.5}, {0.5, y + 1.375 * eps, 0.5});
  for (auto shape : {Shape::Strict, Shape::Coarse}) {
    OptimalSettings settings;
    settings.shape = shape;
    const OptimalResult r = solve_optimal(input, settings);
    const double truth = brute_force(input, OptimalObjective::Fragments, shape, settings.cell_margin);
    EXPECT_EQ(r.upper, truth) << shape_name(shape);
    EXPECT_LE(r.lower, truth) << shape_name(shape) << ": the lower bound is above the optimum";
    EXPECT_LT(truth, static_cast<double>(input.size())) << "the thin triangle was meant to vanish in the optimum";
  }
}

// Larger inputs, where the search meets subproblems again with other bounds to beat, against the
// enumeration with a memo (and no bounds).
TEST(Optimal, MatchesMemoisedEnumerationWhereSubproblemsRecur) {
  const std::pair<OptimalObjective, std::uint32_t> cases[] = {{OptimalObjective::Fragments, 10},
                                                              {OptimalObjective::EPoint, 8},
                                                              {OptimalObjective::ELine, 8}};
  for (const auto& [objective, n] : cases)
    for (const auto& [name, input] : small_scenes(n))
      for (auto shape : {Shape::Strict, Shape::Coarse, Shape::Leafy}) {
        OptimalSettings s;
        s.objective = objective;
        s.shape = shape;
        const OptimalResult r = solve_optimal(input, s);
        const double truth = brute_force(input, objective, shape, s.cell_margin, true);
        const std::string what = name + " n=" + std::to_string(n) + " " + objective_name(objective) + " " + shape_name(shape);
        ASSERT_TRUE(r.optimal()) << what;
        EXPECT_TRUE(close(r.upper, truth)) << what << ": solver " << r.upper << ", enumeration " << truth;
      }
}

// Three segments along the sides of a triangle, none crossing another's line: cutting by A then B
// and by B then A reach one cell holding C. The expected costs' memo must find it again (a key of
// the cell's exact vertices, which list its faces in the order of the cuts, does not), and the
// value must still be the enumeration's.
TEST(Optimal, ACellReachedByCutsInAnotherOrderIsOneSubproblem) {
  const auto seg = [](double ax, double ay, double bx, double by, std::uint32_t source) {
    return Polygon{{Vertex{{ax, ay, 0}}, Vertex{{bx, by, 0}}}, source};
  };
  // Counter-clockwise sides of the triangle (0,0), (4,0), (2,3), each kept off the corners.
  const std::vector<Polygon> input{seg(0.5, 0, 3.5, 0, 0), seg(3.75, 0.375, 2.25, 2.625, 1),
                                   seg(1.75, 2.625, 0.25, 0.375, 2)};
  for (auto objective : {OptimalObjective::EPoint, OptimalObjective::ELine}) {
    OptimalSettings s;
    s.objective = objective;
    const OptimalResult r = solve_optimal(input, s);
    ASSERT_TRUE(r.optimal()) << objective_name(objective);
    EXPECT_GT(r.stats.memo_hits, 0u) << objective_name(objective);
    EXPECT_TRUE(close(r.upper, brute_force(input, objective, Shape::Strict, s.cell_margin))) << objective_name(objective);
  }
}

// Parallel segments stacked in a column: every cell is a slab between two of their lines (or the
// box), and a cut below a slab's floor is redundant once the floor is cut. Keyed by its bounding
// planes alone, each slab is one subproblem, so there are at most (n + 1)(n + 2) / 2 of them; a
// key that kept the redundant planes would count one per set of cuts.
TEST(Optimal, ACellKeepsOnlyThePlanesThatBoundIt) {
  constexpr std::uint32_t n = 10;
  std::vector<Polygon> input;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double y = i;
    const bool up = i % 2 == 0;  // alternate the fronts, so that both sides of a cut hold segments
    input.push_back(Polygon{{Vertex{{up ? 1.0 : 0.0, y, 0}}, Vertex{{up ? 0.0 : 1.0, y, 0}}}, i});
  }
  for (auto objective : {OptimalObjective::EPoint, OptimalObjective::ELine}) {
    OptimalSettings s;
    s.objective = objective;
    const OptimalResult r = solve_optimal(input, s);
    ASSERT_TRUE(r.optimal()) << objective_name(objective);
    EXPECT_LE(r.stats.states, (n + 1) * (n + 2) / 2) << objective_name(objective);
    EXPECT_TRUE(close(r.upper, brute_force(input, objective, Shape::Strict, s.cell_margin, true))) << objective_name(objective);
  }
}

TEST(Optimal, NoAutopartitionHeuristicBeatsTheOptimum) {
  for (const auto& [objective, n] : {std::pair{OptimalObjective::Fragments, 12u}, std::pair{OptimalObjective::EPoint, 8u}})
    for (const auto& [name, input] : small_scenes(n)) {
      OptimalSettings s;
      s.objective = objective;
      const OptimalResult r = solve_optimal(input, s);
      ASSERT_TRUE(r.optimal()) << name;
      EXPECT_LE(r.upper, r.greedy) << name;
      for (const HeuristicInfo& h : heuristics()) {
        if (!h.autopartition) continue;
        const Tree tree = build_tree(input, *make_splitter(h.name, {}, 1));
        EXPECT_GE(experiments::objective_value(tree, input, objective, s.cell_margin), r.lower * (1 - 1e-12))
            << name << " " << h.name << " " << objective_name(objective);
      }
    }
}

TEST(Optimal, ExhaustedBudgetGivesAnIntervalHoldingTheOptimum) {
  const std::vector<Polygon> input =
      make_scene("random-triangles", {{"n", "14"}, {"seed", "2"}, {"size", "0.5"}}).polygons;
  const OptimalResult full = solve_optimal(input, {});
  ASSERT_TRUE(full.optimal());
  OptimalSettings tight;
  tight.max_states = 200;
  const OptimalResult cut = solve_optimal(input, tight);
  EXPECT_TRUE(cut.stats.out_of_states);
  EXPECT_LE(cut.lower, full.upper);
  EXPECT_GE(cut.upper, full.upper);
  EXPECT_EQ(cut.upper, static_cast<double>(cut.tree.fragments.size())) << "the interval's upper end is its tree's";
  EXPECT_EQ(cut.lower, std::floor(cut.lower)) << "a bound on a whole number of fragments is whole";
  EXPECT_EQ(check_tree_invariants(cut.tree, input).violations, 0u);
}

TEST(Optimal, ExhaustedBudgetGivesAnIntervalHoldingTheExpectedCost) {
  const std::vector<Polygon> input = make_scene("random-segments", {{"n", "20"}, {"seed", "2"}}).polygons;
  for (auto objective : {OptimalObjective::EPoint, OptimalObjective::ELine}) {
    OptimalSettings s;
    s.objective = objective;
    const OptimalResult full = solve_optimal(input, s);
    ASSERT_TRUE(full.optimal()) << objective_name(objective);
    s.max_states = 500;
    const OptimalResult cut = solve_optimal(input, s);
    EXPECT_TRUE(cut.stats.out_of_states) << objective_name(objective);
    EXPECT_LE(cut.lower, full.upper * (1 + 1e-12)) << objective_name(objective);
    EXPECT_GE(cut.upper, full.upper * (1 - 1e-12)) << objective_name(objective);
    EXPECT_LE(cut.upper, cut.greedy * (1 + 1e-12)) << objective_name(objective);
    EXPECT_TRUE(close(experiments::objective_value(cut.tree, input, objective, s.cell_margin), cut.upper))
        << objective_name(objective) << ": the interval's upper end is its tree's";
    EXPECT_EQ(check_tree_invariants(cut.tree, input).violations, 0u) << objective_name(objective);
  }
}

TEST(Optimal, TooManyPlanesIsRefused) {
  OptimalSettings s;
  s.max_planes = 5;
  EXPECT_THROW(solve_optimal(make_scene("random-triangles", {{"n", "6"}}).polygons, s), UsageError);
}
