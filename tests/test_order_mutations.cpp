// Mutation tests of the order check: small planted errors in correct back-to-front orders must be
// reported. Which pairs a ray sees in depth order is found here with a plain ray-polygon test,
// independent of the checker (Embree candidates, double-precision decision, tie rule). Each suite
// prints its mutation score (caught / planted); every planted error must be caught.
//  (a) single swaps of two fragments that a ray through one fragment's interior sees in depth order;
//  (b) the two subtrees of a deep node, whose fragments overlap on screen, emitted in swapped order;
//  (c) a coarse leaf's two passes (front-facing, then back-facing) emitted in the wrong order.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <optional>

#include "catalog.h"
#include "split/registry.h"
#include "tree/build.h"
#include "tree/traverse.h"
#include "validate/order_check.h"

using namespace bsp;

namespace {

// A hit is "clear" when it lies inside the polygon by this many scene diagonals and the two hits of
// a pair are this far apart along the ray: far outside any tie the checker may declare.
constexpr double kClearRelative = 1e-4;
constexpr std::size_t kSwaps = 100;

// Ray parameter where the ray meets the convex polygon at least `margin` inside its boundary.
std::optional<double> plain_hit(const Ray& ray, const Polygon& poly, double margin) {
  const Vec3 n = newell_normal(poly);
  const double denom = dot(n, ray.dir);
  if (poly.verts.size() < 3 || denom == 0.0) return std::nullopt;
  const double t = dot(n, poly.verts[0].p - ray.origin) / denom;
  if (!(t > 0.0)) return std::nullopt;
  const Vec3 x = ray.origin + ray.dir * t, unit = normalize(n);
  for (std::size_t i = 0, k = poly.verts.size(); i < k; ++i) {
    const Vec3 e = poly.verts[(i + 1) % k].p - poly.verts[i].p;
    if (dot(cross(e, x - poly.verts[i].p), unit) < margin * length(e)) return std::nullopt;
  }
  return t;
}

Tree build(const std::string& scene_name, int n, const std::string& heuristic, Shape shape) {
  const Scene scene = make_scene(scene_name, {{"n", std::to_string(n)}, {"seed", "3"}});
  auto splitter = make_splitter(heuristic, {}, 3);
  return build_tree(scene.polygons, *splitter, {.shape = shape});
}

// Whether some ray from the eye through a clear interior point of a fragment of `a` clearly meets a
// fragment of `b` at another depth: the two sets overlap on screen.
bool overlap_on_screen(const Tree& tree, const Vec3& eye, const std::vector<std::uint32_t>& a,
                       const std::vector<std::uint32_t>& b) {
  const double clear = kClearRelative * tree.bounds.diagonal();
  for (std::uint32_t f : a) {
    const Ray ray{eye, centroid(tree.fragments[f].polygon()) - eye};
    const auto tf = plain_hit(ray, tree.fragments[f].polygon(), clear);
    if (!tf) continue;
    for (std::uint32_t g : b) {
      const auto tg = plain_hit(ray, tree.fragments[g].polygon(), clear);
      if (tg && std::abs(*tg - *tf) * length(ray.dir) > clear) return true;
    }
  }
  return false;
}

struct Score {
  std::size_t planted = 0, caught = 0;
  void add(bool c) { ++planted, caught += c; }
  void print(const char* what) const {
    std::cout << "mutation score (" << what << "): " << caught << " / " << planted << " caught\n";
  }
};

// True when the checker reports the mutated order; the unmutated one must pass.
class Checker {
 public:
  Checker(const Tree& tree, const Vec3& eye)
      : scene_(tree.fragments.to_polygons(), tree.tol.plane_eps),
        rays_(validation_rays(tree.fragments.to_polygons(), tree.bounds, eye, ValidationSettings{})) {}
  bool catches(std::span<const std::uint32_t> order) const { return check_order(scene_, rays_, order).violations > 0; }

 private:
  EmbreeScene scene_;
  std::vector<Ray> rays_;
};

std::vector<std::uint32_t> positions(const std::vector<std::uint32_t>& order) {
  std::vector<std::uint32_t> pos(order.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) pos[order[i]] = i;
  return pos;
}

// Pairs (f, g) where the ray from the eye through f's centroid clearly meets both, closest in
// depth first: the smallest errors a swap can make.
std::vector<std::pair<std::uint32_t, std::uint32_t>> seen_pairs(const Tree& tree, const Vec3& eye) {
  const double clear = kClearRelative * tree.bounds.diagonal();
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> found;
  for (std::uint32_t f = 0; f < tree.fragments.size(); ++f) {
    const Ray ray{eye, centroid(tree.fragments[f].polygon()) - eye};
    const auto tf = plain_hit(ray, tree.fragments[f].polygon(), clear);
    if (!tf) continue;
    for (std::uint32_t g = 0; g < tree.fragments.size(); ++g) {
      const auto tg = plain_hit(ray, tree.fragments[g].polygon(), clear);
      const double gap = tg ? std::abs(*tg - *tf) * length(ray.dir) : 0.0;
      if (g != f && gap > clear) found.emplace_back(gap, std::min(f, g), std::max(f, g));
    }
  }
  std::sort(found.begin(), found.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& [gap, f, g] : found)
    if (std::find(out.begin(), out.end(), std::make_pair(f, g)) == out.end()) out.emplace_back(f, g);
  return out;
}

TEST(OrderMutations, EverySingleSwapOfTwoFragmentsSeenInDepthOrderIsCaught) {
  const Tree tree = build("random-triangles", 300, "crystal", Shape::Strict);
  const Vec3 eye = validation_eyes(tree.bounds, 1)[0];
  const auto order = visibility_order(tree, eye, Order::BackToFront);
  const Checker checker(tree, eye);
  ASSERT_FALSE(checker.catches(order));
  const auto pairs = seen_pairs(tree, eye);
  ASSERT_GE(pairs.size(), kSwaps);
  const auto pos = positions(order);
  Score score;
  for (std::size_t i = 0; i < kSwaps; ++i) {
    auto mutated = order;
    std::swap(mutated[pos[pairs[i].first]], mutated[pos[pairs[i].second]]);
    score.add(checker.catches(mutated));
  }
  score.print("single swaps");
  EXPECT_EQ(score.caught, score.planted);
}

// Each node's subtree as a list of fragments, and its depth (root 1), by an explicit stack.
struct Subtrees {
  std::vector<std::vector<std::uint32_t>> fragments;
  std::vector<std::uint32_t> depth;
};

Subtrees subtrees(const Tree& tree) {
  Subtrees s{std::vector<std::vector<std::uint32_t>>(tree.nodes.size()), std::vector<std::uint32_t>(tree.nodes.size())};
  std::vector<std::uint32_t> preorder, stack{0};
  s.depth[0] = 1;
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    preorder.push_back(n);
    for (std::uint32_t c : {tree.nodes[n].front, tree.nodes[n].back})
      if (c != kNull) s.depth[c] = s.depth[n] + 1, stack.push_back(c);
  }
  for (auto it = preorder.rbegin(); it != preorder.rend(); ++it) {
    const Node& node = tree.nodes[*it];
    for (std::uint32_t i = tree.fragments_of(*it).begin; i < tree.fragments_of(*it).end; ++i) s.fragments[*it].push_back(i);
    for (std::uint32_t c : {node.front, node.back})
      if (c != kNull) s.fragments[*it].insert(s.fragments[*it].end(), s.fragments[c].begin(), s.fragments[c].end());
  }
  return s;
}

// The order with the node's two subtrees' blocks exchanged (its own fragments stay between them):
// what a traversal that visits the near child first at this node would emit.
std::vector<std::uint32_t> swap_children(const std::vector<std::uint32_t>& order, const std::vector<std::uint32_t>& pos,
                                         const std::vector<std::uint32_t>& first, const std::vector<std::uint32_t>& own,
                                         const std::vector<std::uint32_t>& last) {
  std::uint32_t start = static_cast<std::uint32_t>(order.size());
  for (const auto* block : {&first, &own, &last})
    for (std::uint32_t f : *block) start = std::min(start, pos[f]);
  auto sorted = [&](std::vector<std::uint32_t> b) {
    std::sort(b.begin(), b.end(), [&](std::uint32_t x, std::uint32_t y) { return pos[x] < pos[y]; });
    return b;
  };
  auto mutated = order;
  std::uint32_t at = start;
  for (const auto& block : {sorted(last), sorted(own), sorted(first)})
    for (std::uint32_t f : block) mutated[at++] = f;
  return mutated;
}

TEST(OrderMutations, SwappedChildrenOfDeepNodesOverlappingOnScreenAreCaught) {
  constexpr std::uint32_t kMinDepth = 6;
  const Tree tree = build("random-triangles", 600, "crystal", Shape::Strict);
  const Vec3 eye = validation_eyes(tree.bounds, 1)[0];
  const auto order = visibility_order(tree, eye, Order::BackToFront);
  const auto pos = positions(order);
  const Checker checker(tree, eye);
  const Subtrees s = subtrees(tree);
  Score score;
  for (std::uint32_t n = 0; n < tree.nodes.size(); ++n) {
    const Node& node = tree.nodes[n];
    if (s.depth[n] < kMinDepth || node.front == kNull || node.back == kNull) continue;
    const auto& front = s.fragments[node.front];
    const auto& back = s.fragments[node.back];
    if (!overlap_on_screen(tree, eye, front, back)) continue;
    std::vector<std::uint32_t> own;
    for (std::uint32_t i = tree.fragments_of(n).begin; i < tree.fragments_of(n).end; ++i) own.push_back(i);
    const bool back_first = pos[back.front()] < pos[front.front()];
    score.add(checker.catches(swap_children(order, pos, back_first ? back : front, own, back_first ? front : back)));
  }
  score.print("swapped children");
  EXPECT_GE(score.planted, 50u);
  EXPECT_EQ(score.caught, score.planted);
}

// Every coarse leaf whose front-facing and back-facing fragments overlap on screen from the eye gets
// its passes exchanged, one leaf at a time.
void plant_pass_swaps(const Tree& tree, const Vec3& eye, Score& score) {
  const auto order = visibility_order(tree, eye, Order::BackToFront);
  const auto pos = positions(order);
  const Checker checker(tree, eye);
  ASSERT_FALSE(checker.catches(order));
  for (std::uint32_t n = 0; n < tree.nodes.size(); ++n) {
    if (!tree.nodes[n].is_cell_leaf()) continue;
    std::vector<std::uint32_t> facing, away;
    for (std::uint32_t i = tree.fragments_of(n).begin; i < tree.fragments_of(n).end; ++i)
      (tree.planes[tree.fragment_plane[i]].distance(eye) >= -tree.tol.plane_eps ? facing : away).push_back(i);
    if (facing.empty() || away.empty() || !overlap_on_screen(tree, eye, facing, away)) continue;
    score.add(checker.catches(swap_children(order, pos, facing, {}, away)));
  }
}

TEST(OrderMutations, ACoarseLeafsPassesInTheWrongOrderAreCaught) {
  Score score;
  for (const char* scene : {"random-triangles", "city", "architecture", "terrain"}) {
    const Tree tree = build(scene, 300, "random", Shape::Coarse);
    for (const Vec3& eye : validation_eyes(tree.bounds, 4)) plant_pass_swaps(tree, eye, score);
  }
  score.print("coarse leaf passes");
  EXPECT_GE(score.planted, 20u);
  EXPECT_EQ(score.caught, score.planted);
}

}  // namespace
