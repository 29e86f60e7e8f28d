#include "io/polygon_cleanup.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <tuple>

namespace bsp {

namespace {

struct Point2 {
  double x, y;
};

// Twice the signed area of (a, b, c): positive when they turn counter-clockwise.
double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

double distance(const Point2& a, const Point2& b) { return std::hypot(b.x - a.x, b.y - a.y); }

// The polygon in an orthonormal frame (u, v) of its Newell plane with cross(u, v) along the normal,
// so a polygon counter-clockwise about its normal is counter-clockwise in 2D. Empty when degenerate.
std::vector<Point2> project(const Polygon& poly) {
  const Vec3 n = newell_normal(poly);
  const double len = length(n);
  if (!(len > 0.0) || !std::isfinite(len)) return {};
  const Vec3 w = n / len;
  const Vec3 u = normalize(cross(std::abs(w.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}, w));
  const Vec3 v = cross(w, u);
  std::vector<Point2> out;
  out.reserve(poly.verts.size());
  for (const auto& x : poly.verts) out.push_back({dot(x.p, u), dot(x.p, v)});
  return out;
}

bool has_repeated_position(const Polygon& poly) {
  std::vector<std::tuple<double, double, double>> p;
  for (const auto& v : poly.verts) p.emplace_back(v.p.x, v.p.y, v.p.z);
  std::sort(p.begin(), p.end());
  return std::adjacent_find(p.begin(), p.end()) != p.end();
}

// The x direction of a convex polygon's edges changes sign at most twice going round.
bool winds_once(const std::vector<Point2>& q, double eps) {
  int changes = 0, last = 0;
  for (std::size_t i = 0, k = q.size(); i <= k; ++i) {  // one past the end to compare the wrap
    const double dx = q[(i + 1) % k].x - q[i % k].x;
    const int sign = dx > eps ? 1 : (dx < -eps ? -1 : 0);
    if (sign == 0) continue;
    if (last != 0 && sign != last) ++changes;
    last = sign;
  }
  return changes <= 2;
}

bool inside_or_on(const Point2& p, const Point2& a, const Point2& b, const Point2& c) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

class EarClipper {
 public:
  EarClipper(const Polygon& poly, std::vector<Point2> q, double eps)
      : poly_(poly), q_(std::move(q)), eps_(eps), idx_(q_.size()) {
    std::iota(idx_.begin(), idx_.end(), std::size_t{0});
  }

  std::vector<Polygon> run() {
    while (idx_.size() >= 3) {
      if (remove_straight_vertex()) continue;
      clip(find_ear().value_or(most_convex()));
    }
    return std::move(out_);
  }

 private:
  std::size_t at(std::size_t t) const { return idx_[t % idx_.size()]; }
  const Point2& pt(std::size_t t) const { return q_[at(t)]; }
  std::size_t prev(std::size_t t) const { return t + idx_.size() - 1; }

  // A vertex within eps of the line through its neighbours bounds no area: drop it, no triangle.
  bool remove_straight_vertex() {
    for (std::size_t t = 0; t < idx_.size(); ++t)
      if (std::abs(orient(pt(prev(t)), pt(t), pt(t + 1))) <= eps_ * distance(pt(prev(t)), pt(t + 1))) {
        idx_.erase(idx_.begin() + static_cast<std::ptrdiff_t>(t));
        return true;
      }
    return false;
  }

  bool is_ear(std::size_t t) const {
    const Point2 &a = pt(prev(t)), &b = pt(t), &c = pt(t + 1);
    if (orient(a, b, c) <= 0) return false;
    for (std::size_t s = 2; s + 1 < idx_.size(); ++s)
      if (inside_or_on(pt(t + s), a, b, c)) return false;
    return true;
  }

  std::optional<std::size_t> find_ear() const {
    for (std::size_t s = 0; s < idx_.size(); ++s)
      if (is_ear((start_ + s) % idx_.size())) return (start_ + s) % idx_.size();
    return std::nullopt;
  }

  // Only reached when the projection is not simple (a self-crossing or folded face).
  std::size_t most_convex() const {
    std::size_t best = 0;
    for (std::size_t t = 1; t < idx_.size(); ++t)
      if (orient(pt(prev(t)), pt(t), pt(t + 1)) > orient(pt(prev(best)), pt(best), pt(best + 1))) best = t;
    return best;
  }

  void clip(std::size_t t) {
    out_.push_back({{poly_.verts[at(prev(t))], poly_.verts[at(t)], poly_.verts[at(t + 1)]}, poly_.source});
    idx_.erase(idx_.begin() + static_cast<std::ptrdiff_t>(t));
    start_ = t;  // the next ear is usually next to this one
  }

  const Polygon& poly_;
  std::vector<Point2> q_;
  double eps_;
  std::vector<std::size_t> idx_;  // remaining vertices, in order
  std::size_t start_ = 0;
  std::vector<Polygon> out_;
};

}  // namespace

bool is_convex_planar(const Polygon& poly, double eps) {
  const auto plane = supporting_plane(poly);
  if (!plane) return false;
  for (const auto& x : poly.verts)
    if (std::abs(plane->distance(x.p)) > eps) return false;
  const auto q = project(poly);
  const std::size_t k = q.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Point2 &a = q[i], &b = q[(i + 1) % k], &c = q[(i + 2) % k];
    const double turn = orient(a, b, c);
    if (turn < -eps * distance(a, b)) return false;
    // A straight turn back (a spike) passes the orientation test but folds the boundary over itself.
    const bool reverses = (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) < 0;
    if (turn <= eps * distance(a, c) && reverses) return false;
  }
  return winds_once(q, eps);
}

std::vector<Polygon> ear_clip(const Polygon& poly, double eps) {
  auto q = project(poly);
  if (q.size() < 3) return {};
  return EarClipper(poly, std::move(q), eps).run();
}

void append_clean_polygon(Polygon&& poly, double eps, std::vector<Polygon>& out, SceneLoadStats& stats) {
  if (has_repeated_position(poly)) {
    ++stats.dropped_duplicate_vertex;
    return;
  }
  if (poly.verts.size() < 3 || is_sliver(poly, eps)) {
    ++stats.dropped_degenerate;
    return;
  }
  if (is_convex_planar(poly, eps)) {
    out.push_back(std::move(poly));
    return;
  }
  ++stats.triangulated;
  for (auto& t : ear_clip(poly, eps)) out.push_back(std::move(t));
}

}  // namespace bsp
