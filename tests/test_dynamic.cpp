// Animated scenes and the dynamic-scene updaters: frames are a deterministic function of the spec,
// objects stay in the static box and advance exactly `speed` diagonals per frame along their
// paths, adding an object moves no other, bad specs are refused; rebuild's tree of every frame is
// the plain build of that frame and passes the invariants and the Embree order check; so does every
// frame of every other strategy, bit for bit the same on a second run. reinsert-each repairs every
// frame where reinsert repairs only once; merge never edits the static tree; torres moves objects
// that stay in their cells in place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "animation.h"
#include "catalog.h"
#include "common/errors.h"
#include "dynamic/object_tree.h"
#include "dynamic/updater.h"
#include "split/registry.h"
#include "validate/order_check.h"
#include "validate/tree_invariants.h"

using namespace bsp;

namespace {

AnimationSpec small_spec() {
  AnimationSpec s;
  s.scene = "architecture";
  s.scene_params = {{"n", "300"}};
  s.moving = 3;
  s.frames = 6;
  s.object_n = 48;
  s.speed = 0.01;
  return s;
}

Vec3 object_centre(const Animation& a, std::size_t i, std::uint32_t frame) {
  Vec3 sum;
  std::size_t n = 0;
  for (const Polygon& p : a.object_at(i, frame))
    for (const Vertex& v : p.verts) sum += v.p, ++n;
  return sum / static_cast<double>(n);
}

}  // namespace

TEST(Animation, SameSpecGivesTheSameFramesAndAnotherSeedOthers) {
  const Animation a(small_spec()), b(small_spec());
  AnimationSpec other = small_spec();
  other.seed = 2;
  const Animation c(other);
  for (std::uint32_t f : {0u, 3u, 5u}) {
    EXPECT_EQ(content_hash(a.frame(f)), content_hash(b.frame(f))) << f;
    EXPECT_NE(content_hash(a.frame(f)), content_hash(c.frame(f))) << f;
  }
  EXPECT_NE(content_hash(a.frame(0)), content_hash(a.frame(1)));
  EXPECT_EQ(a.frame(2).polygons.size(), a.static_scene().polygons.size() + 3 * a.object_polygons());
}

TEST(Animation, ObjectsStayInTheBoxAndAdvanceSpeedDiagonalsPerFrame) {
  AnimationSpec s = small_spec();
  s.frames = 400;
  const Animation a(s);
  const Box box = bounds(a.static_scene());
  const double step = s.speed * box.diagonal(), radius = s.size * box.diagonal();
  std::size_t exact_steps = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::uint32_t f = 0; f + 1 < s.frames; f += 7) {
      const Vec3 p = object_centre(a, i, f), q = object_centre(a, i, f + 1);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p[k], box.lo[k] - radius);
        EXPECT_LE(p[k], box.hi[k] + radius);
      }
      // A step that turns a waypoint is shorter than the path length it covers.
      const double d = length(q - p);
      EXPECT_LE(d, step * (1 + 1e-9));
      exact_steps += std::abs(d - step) <= 1e-9 * step;
    }
  EXPECT_GT(exact_steps, 100u);
}

TEST(Animation, AddingAnObjectMovesNoOther) {
  AnimationSpec two = small_spec(), three = small_spec();
  two.moving = 2;
  const Animation a(two), b(three);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::uint32_t f : {0u, 4u}) {
      const auto x = a.object_at(i, f), y = b.object_at(i, f);
      ASSERT_EQ(x.size(), y.size());
      for (std::size_t k = 0; k < x.size(); ++k) EXPECT_EQ(x[k].verts[0].p, y[k].verts[0].p);
    }
}

TEST(Animation, OpenObjectsAndValuesOutOfRangeAreRefused) {
  const auto refused = [](auto change) {
    AnimationSpec s = small_spec();
    change(s);
    EXPECT_THROW(Animation{s}, UsageError);
  };
  refused([](AnimationSpec& s) { s.object = "city"; });
  refused([](AnimationSpec& s) { s.frames = 0; });
  refused([](AnimationSpec& s) { s.size = 0; });
  refused([](AnimationSpec& s) { s.speed = -0.1; });
  refused([](AnimationSpec& s) { s.moving = 1001; });
  EXPECT_THROW(make_updater("teleport", make_splitter("first", {}, 1), make_splitter("first", {}, 1)), UsageError);
}

bool same_tree(const Tree& a, const Tree& b) {
  if (a.nodes.size() != b.nodes.size() || a.fragments.size() != b.fragments.size()) return false;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const Node &x = a.nodes[i], &y = b.nodes[i];
    if (x.plane != y.plane || x.front != y.front || x.back != y.back || x.first != y.first) return false;
  }
  for (std::size_t f = 0; f < a.fragments.size(); ++f) {
    const auto p = a.fragments.points(f), q = b.fragments.points(f);
    if (a.fragments[f].source != b.fragments[f].source || !std::equal(p.begin(), p.end(), q.begin(), q.end()))
      return false;
  }
  return true;
}

// rebuild's tree of each frame is the plain build of that frame, node for node and vertex for
// vertex, and valid. The splitter is randomised (random), so reusing its state across frames would
// show.
TEST(RebuildUpdater, EveryFrameIsThePlainBuildAndPassesTheChecks) {
  const Animation a(small_spec());
  auto u = make_updater("rebuild", make_splitter("random", {}, 7), make_splitter("random", {}, 7));
  const Scene frame0 = a.frame(0);
  const std::span<const Polygon> still(frame0.polygons.data(), a.static_scene().polygons.size());
  const auto first = static_cast<std::uint32_t>(still.size());
  ValidationSettings views;
  views.views = 2;
  for (std::uint32_t f = 0; f < a.spec().frames; ++f) {
    const std::vector<Polygon> moving = a.moving_at(f, first);
    const UpdateWork w = f == 0 ? u->start(still, moving, 3) : u->update(moving);
    EXPECT_EQ(w.polygons_built, still.size() + moving.size());
    const Scene scene = a.frame(f);
    auto splitter = make_splitter("random", {}, 7);
    EXPECT_TRUE(same_tree(u->tree(), build_tree(scene.polygons, *splitter))) << f;
    EXPECT_EQ(check_tree_invariants(u->tree(), scene.polygons).violations, 0u) << f;
    EXPECT_EQ(validate_tree(u->tree(), views).violations, 0u) << f;
  }
}

namespace {

struct StrategyRun {
  std::vector<Tree> trees;       // every frame's
  std::vector<UpdateWork> work;  // every frame's (frame 0: start)
};

StrategyRun run_strategy(const AnimationSpec& spec, const std::string& strategy, const std::string& heuristic,
                         bool check) {
  const Animation a(spec);
  auto u = make_updater(strategy, make_splitter(heuristic, {}, 5),
                        make_splitter(strategy == "torres" ? "halving" : heuristic, {}, 5));
  const Scene frame0 = a.frame(0);
  const std::span<const Polygon> still(frame0.polygons.data(), a.static_scene().polygons.size());
  ValidationSettings views;
  views.views = 2;
  StrategyRun run;
  for (std::uint32_t f = 0; f < spec.frames; ++f) {
    const Scene scene = a.frame(f);
    const auto moving = std::span<const Polygon>(scene.polygons).subspan(still.size());
    run.work.push_back(f == 0 ? u->start(still, moving, spec.moving) : u->update(moving));
    run.trees.push_back(u->tree());
    if (!check) continue;
    const InvariantReport inv = check_tree_invariants(u->tree(), scene.polygons);
    EXPECT_EQ(inv.violations, 0u) << strategy << " " << heuristic << " frame " << f << ": "
                                  << (inv.first_problems.empty() ? "" : inv.first_problems[0]);
    EXPECT_EQ(validate_tree(u->tree(), views).violations, 0u) << strategy << " " << heuristic << " frame " << f;
  }
  return run;
}

const std::vector<std::string> kTreeKeeping = {"reinsert", "reinsert-each", "merge", "torres"};

}  // namespace

TEST(DynamicStrategies, EveryFrameOfEveryStrategyPassesTheChecks) {
  AnimationSpec s = small_spec();
  s.frames = 8;
  for (const auto& strategy : kTreeKeeping)
    for (const std::string heuristic : {"crystal", "naylor", "random"}) run_strategy(s, strategy, heuristic, true);
}

// Objects crossing each other and the static geometry at close range: many objects, fast.
TEST(DynamicStrategies, CrowdedFastObjectsPassTheChecks) {
  AnimationSpec s = small_spec();
  s.scene = "city";
  s.moving = 12;
  s.object_n = 24;
  s.size = 0.06;
  s.speed = 0.03;
  s.frames = 10;
  for (const auto& strategy : kTreeKeeping) run_strategy(s, strategy, "crystal", true);
}

TEST(DynamicStrategies, ASecondRunGivesTheSameTreesBitForBit) {
  for (const auto& strategy : kTreeKeeping) {
    const StrategyRun a = run_strategy(small_spec(), strategy, "random", false);
    const StrategyRun b = run_strategy(small_spec(), strategy, "random", false);
    for (std::size_t f = 0; f < a.trees.size(); ++f) EXPECT_TRUE(same_tree(a.trees[f], b.trees[f])) << strategy << f;
  }
}

TEST(DynamicStrategies, CoarseTreesAndIncrementalBuildsAreRefused) {
  BuildOptions coarse;
  coarse.shape = Shape::Coarse;
  BuildOptions incremental;
  incremental.incremental = true;
  for (const auto& strategy : kTreeKeeping)
    for (const BuildOptions& o : {coarse, incremental})
      EXPECT_THROW(make_updater(strategy, make_splitter("first", {}, 1), make_splitter("first", {}, 1), o), UsageError);
}

// The first frame's tree is one build of everything, so objects' planes sit above static
// fragments: the first update repairs. Afterwards reinsert (all objects out, then all in) never
// repairs; reinsert-each puts each object back below the nodes of objects still to come out.
TEST(ReinsertUpdater, RemovedNodesWithTwoNonEmptySubtreesAreRepaired) {
  AnimationSpec s = small_spec();
  s.scene = "city";
  s.moving = 8;
  s.frames = 5;
  const StrategyRun all = run_strategy(s, "reinsert", "crystal", true);
  const StrategyRun each = run_strategy(s, "reinsert-each", "crystal", true);
  EXPECT_GT(all.work[1].repairs, 0u);
  EXPECT_GT(all.work[1].reinserted_fragments, 0u);
  std::uint64_t later_all = 0, later_each = 0;
  for (std::size_t f = 2; f < all.work.size(); ++f) {
    later_all += all.work[f].repairs;
    later_each += each.work[f].repairs;
  }
  EXPECT_EQ(later_all, 0u);
  EXPECT_GT(later_each, 0u);
}

// The static polygons' fragments, in traversal order: merge must leave them exactly as built.
std::vector<std::vector<Vec3>> static_fragments(const Tree& t, std::uint32_t static_count) {
  std::vector<std::vector<Vec3>> out;
  for (std::size_t f = 0; f < t.fragments.size(); ++f)
    if (t.fragments[f].source < static_count) {
      const auto p = t.fragments.points(f);
      out.emplace_back(p.begin(), p.end());
    }
  return out;
}

TEST(MergeUpdater, NeverEditsTheStaticTree) {
  const Animation a(small_spec());
  const auto statics = static_cast<std::uint32_t>(a.static_scene().polygons.size());
  const StrategyRun run = run_strategy(small_spec(), "merge", "crystal", false);
  for (std::size_t f = 1; f < run.trees.size(); ++f) {
    EXPECT_EQ(static_fragments(run.trees[f], statics), static_fragments(run.trees[0], statics)) << f;
    EXPECT_EQ(run.work[f].polygons_built, 0u);
    EXPECT_EQ(run.work[f].objects_placed, small_spec().moving);
  }
  // The comparison sees edits: reinsert's first update repairs, splitting static fragments.
  const StrategyRun edited = run_strategy(small_spec(), "reinsert", "crystal", false);
  ASSERT_GT(edited.work[1].repairs, 0u);
  EXPECT_NE(static_fragments(edited.trees[1], statics), static_fragments(edited.trees[0], statics));
}

// Small slow objects in a sparse scene stay in their cells: torres moves them in place, and those
// frames still pass every check (run_strategy checks them).
TEST(TorresUpdater, ObjectsThatStayInTheirCellsMoveInPlace) {
  AnimationSpec s = small_spec();
  s.scene_params = {{"n", "60"}};
  s.size = 0.01;
  s.speed = 0.002;
  s.frames = 10;
  const StrategyRun run = run_strategy(s, "torres", "crystal", true);
  std::uint64_t moved = 0, placed = 0;
  for (std::size_t f = 1; f < run.work.size(); ++f) {
    moved += run.work[f].moved_nodes;
    placed += run.work[f].objects_placed;
  }
  EXPECT_GT(moved, 0u);
  EXPECT_LT(placed, s.moving * (s.frames - 1));
}

TEST(RigidMotion, RecoversARotationAndATranslationFromThreePoints) {
  const Vec3 a[3] = {{0.3, -1, 2}, {1.7, 0.2, 2.5}, {-0.4, 0.9, 1.1}};
  const Vec3 axis = normalize(Vec3{1, 2, -0.5});
  const double angle = 0.7;
  const auto turn = [&](const Vec3& p) {  // Rodrigues
    return p * std::cos(angle) + cross(axis, p) * std::sin(angle) + axis * dot(axis, p) * (1 - std::cos(angle));
  };
  const Vec3 shift{5, -3, 0.25};
  const Vec3 b[3] = {turn(a[0]) + shift, turn(a[1]) + shift, turn(a[2]) + shift};
  const RigidMotion m = motion_between(a, b);
  const Vec3 q{-2, 4, 7};
  EXPECT_LT(length(m.apply(q) - (turn(q) + shift)), 1e-12);
  const Plane p = Plane::through(Vec3{0.2, 0.3, 1}, q);
  const Plane moved = m.apply(p);
  EXPECT_LT(std::abs(moved.distance(turn(q) + shift)), 1e-12);
  EXPECT_LT(length(moved.n - turn(p.n)), 1e-12);
}

// Objects made of the scene's own polygons: K disjoint groups of object_n polygons leave the static
// scene (which keeps the rest) and move rigidly (each polygon keeps its area); every strategy keeps
// them with every frame passing the checks.
TEST(Animation, SceneGroupsLeaveTheSceneAndMoveRigidly) {
  AnimationSpec s = small_spec();
  s.scene = "city";
  s.object = std::string(kSceneGroups);
  s.object_n = 20;
  s.frames = 5;
  const Animation a(s);
  const Scene whole = make_scene("city", s.scene_params);
  ASSERT_EQ(a.static_scene().polygons.size() + 3 * 20, whole.polygons.size());
  EXPECT_EQ(a.object_polygons(), 20u);
  const auto first = static_cast<std::uint32_t>(a.static_scene().polygons.size());
  const std::vector<Polygon> at0 = a.moving_at(0, first), at4 = a.moving_at(4, first);
  ASSERT_EQ(at0.size(), 60u);
  double total = 0;
  for (std::size_t i = 0; i < at0.size(); ++i) {
    EXPECT_NEAR(area(at0[i]), area(at4[i]), 1e-9 * area(at0[i]));
    total += area(at0[i]);
  }
  double whole_area = 0, static_area = 0;
  for (const Polygon& p : whole.polygons) whole_area += area(p);
  for (const Polygon& p : a.static_scene().polygons) static_area += area(p);
  EXPECT_NEAR(static_area + total, whole_area, 1e-9 * whole_area);
  for (const auto& strategy : kTreeKeeping) run_strategy(s, strategy, "crystal", true);
  AnimationSpec too_many = s;
  too_many.object_n = 100000;
  EXPECT_THROW(Animation{too_many}, UsageError);
}
