#include "metrics/ray_shoot.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bsp {

namespace {

// The walk clips rays to the scene box grown by this fraction of its diagonal (at least this much
// absolutely, vec3.h Box::enlarged), so fragments on the box's faces are inside the clip.
constexpr double kClipMargin = 1e-6;

struct Segment {
  double t0, t1;
};

// Slab clip of the ray (t > 0) to the box; nullopt when it misses.
std::optional<Segment> clip(const Ray& ray, const Box& box) {
  Segment s{0.0, 1e300};
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a], d = ray.dir[a], lo = box.lo[a], hi = box.hi[a];
    if (d == 0.0) {
      if (o < lo || o > hi) return std::nullopt;
      continue;
    }
    const double ta = (lo - o) / d, tb = (hi - o) / d;
    s.t0 = std::max(s.t0, std::min(ta, tb));
    s.t1 = std::min(s.t1, std::max(ta, tb));
  }
  if (s.t0 > s.t1) return std::nullopt;
  return s;
}

struct Step {
  std::uint32_t node;
  double t0, t1;
  bool stored_only;  // test only the fragments stored at the node (the plane crossing)
};

class Walker {
 public:
  Walker(const Tree& tree, const Ray& ray) : tree_(tree), ray_(ray) {}

  RayShot run() {
    const std::optional<Segment> root = clip(ray_, tree_.bounds.enlarged(kClipMargin));
    if (tree_.empty() || !root) return shot_;
    stack_.push_back({0, root->t0, root->t1, false});
    while (!stack_.empty()) {
      const Step s = stack_.back();
      stack_.pop_back();
      if (shot_.hit && s.t0 >= shot_.hit->t) break;
      if (s.stored_only) {
        test_fragments(tree_.nodes[s.node]);
        continue;
      }
      visit(s);
    }
    return shot_;
  }

 private:
  void visit(const Step& s) {
    ++shot_.nodes_visited;
    const Node& node = tree_.nodes[s.node];
    if (node.is_cell_leaf()) {
      test_fragments(node);
      return;
    }
    const Plane& plane = tree_.planes[node.plane];
    const double d0 = plane.distance(ray_.origin), rate = dot(plane.n, ray_.dir);
    const double da = d0 + s.t0 * rate, db = d0 + s.t1 * rate;
    const bool a_front = da > 0, b_front = db > 0;
    if (a_front == b_front) {
      // Wholly on one side; a segment ending on the plane may still meet its fragments there.
      const std::uint32_t side = a_front ? node.front : node.back;
      if (side != kNull) stack_.push_back({side, s.t0, s.t1, false});
      const double eps = tree_.tol.plane_eps;
      if (std::abs(da) <= eps || std::abs(db) <= eps) test_fragments(node);
      return;
    }
    const double tc = std::clamp(-d0 / rate, s.t0, s.t1);
    const std::uint32_t near_side = a_front ? node.front : node.back;
    const std::uint32_t far_side = a_front ? node.back : node.front;
    if (far_side != kNull) stack_.push_back({far_side, tc, s.t1, false});
    if (node.count) stack_.push_back({s.node, tc, tc, true});
    if (near_side != kNull) stack_.push_back({near_side, s.t0, tc, false});
  }

  void test_fragments(const Node& node) {
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
      ++shot_.fragment_tests;
      const auto t = ray_polygon_hit(ray_, tree_.fragments[i], tree_.planes[tree_.fragment_plane[i]]);
      if (t && (!shot_.hit || *t < shot_.hit->t)) shot_.hit = Hit{*t, i};
    }
  }

  const Tree& tree_;
  const Ray& ray_;
  RayShot shot_;
  std::vector<Step> stack_;
};

}  // namespace

std::optional<double> ray_polygon_hit(const Ray& ray, const Polygon& poly, const Plane& support) {
  const auto& v = poly.verts;
  bool pos = true, neg = true;  // every Plücker product so far is >= 0 / <= 0
  for (std::size_t i = 0, k = v.size(); i < k && (pos || neg); ++i) {
    const double s = dot(ray.dir, cross(v[i].p - ray.origin, v[(i + 1) % k].p - ray.origin));
    pos &= s >= 0;
    neg &= s <= 0;
  }
  if (!pos && !neg) return std::nullopt;
  const double rate = dot(support.n, ray.dir);
  if (rate == 0.0) return std::nullopt;
  const double t = -support.distance(ray.origin) / rate;
  if (!(t > 0) || !std::isfinite(t)) return std::nullopt;
  return t;
}

RayShot shoot_ray(const Tree& tree, const Ray& ray) { return Walker(tree, ray).run(); }

}  // namespace bsp
