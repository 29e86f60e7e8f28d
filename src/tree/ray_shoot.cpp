#include "tree/ray_shoot.h"

#include <algorithm>
#include <cmath>
#include <tuple>
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
      if (shot_.hit && s.t0 >= shot_.hit->t) continue;
      if (s.stored_only) {
        test_fragments(s.node);
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
      test_fragments(s.node);
      return;
    }
    const Plane& plane = tree_.planes[node.plane];
    const double d0 = plane.distance(ray_.origin), rate = dot(plane.n, ray_.dir);
    const double da = d0 + s.t0 * rate, db = d0 + s.t1 * rate;
    const bool front_first = da > 0 || (da == 0 && rate < 0);
    const Segment first = within(front_first ? 1.0 : -1.0, d0, rate, s), last = within(front_first ? -1.0 : 1.0, d0, rate, s);
    const std::uint32_t first_side = front_first ? node.front : node.back;
    const std::uint32_t last_side = front_first ? node.back : node.front;
    if (last_side != kNull && last.t0 <= last.t1) stack_.push_back({last_side, last.t0, last.t1, false});
    const bool near_plane = (da <= 0) != (db <= 0) || std::min(std::abs(da), std::abs(db)) <= tree_.tol.plane_eps;
    if (tree_.fragments_of(s.node).size() > 0 && near_plane) stack_.push_back({s.node, last.t0, last.t0, true});
    if (first_side != kNull && first.t0 <= first.t1) stack_.push_back({first_side, first.t0, first.t1, false});
  }

  // The part of the segment where side * distance > -plane_eps (side +1: the front half-space
  // grown by the tolerance, -1: the back one); t0 > t1 when there is none.
  Segment within(double side, double d0, double rate, const Step& s) const {
    const double eps = tree_.tol.plane_eps, d = side * d0, r = side * rate;
    if (r == 0.0) return d > -eps ? Segment{s.t0, s.t1} : Segment{1.0, 0.0};
    const double edge = (-eps - d) / r;
    return r > 0 ? Segment{std::max(s.t0, edge), s.t1} : Segment{s.t0, std::min(s.t1, edge)};
  }

  void test_fragments(std::uint32_t node) {
    const FragmentRange r = tree_.fragments_of(node);
    for (std::uint32_t i = r.begin; i < r.end; ++i) {
      ++shot_.fragment_tests;
      const auto t = ray_polygon_hit(ray_, tree_.fragments.points(i), tree_.planes[tree_.fragment_plane[i]]);
      if (t && (!shot_.hit || *t < shot_.hit->t)) shot_.hit = RayHit{*t, i};
    }
  }

  const Tree& tree_;
  const Ray& ray_;
  RayShot shot_;
  std::vector<Step> stack_;
};

// The ray's Plücker product with the edge a -> b (ray_shoot.h), computed from the edge's
// lexicographically smaller end, so that the edge b -> a gets exactly the opposite value.
double plucker_side(const Ray& ray, const Vec3& a, const Vec3& b) {
  const bool a_first = std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  const Vec3& u = a_first ? a : b;
  const Vec3& w = a_first ? b : a;
  const double s = dot(w - u, cross(ray.dir, u - ray.origin));
  return a_first ? s : -s;
}

}  // namespace

std::optional<double> ray_polygon_hit(const Ray& ray, std::span<const Vec3> v, const Plane& support) {
  bool pos = true, neg = true;  // every Plücker product so far is >= 0 / <= 0
  for (std::size_t i = 0, k = v.size(); i < k && (pos || neg); ++i) {
    const double s = plucker_side(ray, v[i], v[(i + 1) % k]);
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
