// Animated scenes and the dynamic-scene updaters: frames are a deterministic function of the spec,
// objects stay in the static box and advance exactly `speed` diagonals per frame along their
// paths, adding an object moves no other, bad specs are refused; rebuild's tree of every frame is
// the plain build of that frame and passes the invariants and the Embree order check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "animation.h"
#include "common/errors.h"
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
  EXPECT_THROW(make_updater("teleport", make_splitter("first", {}, 1)), UsageError);
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
  auto u = make_updater("rebuild", make_splitter("random", {}, 7));
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
