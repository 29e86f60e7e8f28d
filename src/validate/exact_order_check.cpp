#include "validate/exact_order_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "tree/exact_traverse.h"
#include "validate/embree_scene.h"

namespace bsp {

namespace {

using Wide = WideInt<5>;
constexpr std::size_t kRaysPerBatch = 64;
// A thread's pair keys are sorted and deduplicated once they exceed this many, which bounds memory
// on views whose rays cross many fragments (as the float check does, order_check.cpp).
constexpr std::size_t kCompactAt = std::size_t{1} << 22;
// Every this many rays of a view (or fewer, under kRecoverBudget) is also searched exhaustively
// (exact_order_check.h), besides the rays where a proposal was refused.
constexpr std::size_t kExhaustiveEvery = 64;
// Fragment tests each kind of search (sampled rays, rays with a refusal) may spend per view: where
// rays and fragments are many (saddle-grid with halving: 2.4 * 10^5 fragments, 10^6 refusals), only
// every stride-th ray qualifies, a stride chosen from the view's rays and fragments, so the search
// costs about a second at most and the same rays are searched on any thread count.
constexpr double kRecoverBudget = 0x1p26;
// The exhaustive search skips a fragment whose bounding box, grown by this much of the scene's
// extent (diagonal plus the largest coordinate's magnitude), the ray misses in doubles. The view's
// vertices lie within a few units in the last place of the exact ones, and the slab test rounds a
// few times more, both far below this: the skip never loses a hit, it only saves the exact test.
constexpr double kRecoverBoxMargin = 1e-9;

// Whether the ray from `o` along `d` (t >= 0) meets the box, in doubles.
bool ray_meets_box(const Vec3& o, const Vec3& d, const Box& b) {
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  const double os[] = {o.x, o.y, o.z}, ds[] = {d.x, d.y, d.z}, bl[] = {b.lo.x, b.lo.y, b.lo.z}, bh[] = {b.hi.x, b.hi.y, b.hi.z};
  for (int k = 0; k < 3; ++k) {
    if (ds[k] == 0) {
      if (os[k] < bl[k] || os[k] > bh[k]) return false;
      continue;
    }
    double t0 = (bl[k] - os[k]) / ds[k], t1 = (bh[k] - os[k]) / ds[k];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return false;
  }
  return true;
}

// Each fragment's box of its view's vertices, grown by kRecoverBoxMargin.
std::vector<Box> recover_boxes(const std::vector<Polygon>& fragments, const Box& bounds) {
  const double extent = bounds.diagonal() + std::max({std::abs(bounds.lo.x), std::abs(bounds.lo.y), std::abs(bounds.lo.z),
                                                      std::abs(bounds.hi.x), std::abs(bounds.hi.y), std::abs(bounds.hi.z)});
  const double m = kRecoverBoxMargin * extent;
  std::vector<Box> out(fragments.size());
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    for (const Vertex& v : fragments[f].verts) out[f].add(v.p);
    out[f] = {out[f].lo - Vec3{m, m, m}, out[f].hi + Vec3{m, m, m}};
  }
  return out;
}

Wide wide(std::int64_t v) { return Wide(Int128{v}); }

struct ExactRay {
  GridPoint eye, dir;  // points eye + t dir
};

// The plane's value at the eye and its normal's product with the direction.
struct Meeting {
  Wide value, slope;  // S(E), A . D
};

Meeting meeting(const GridPlane& p, const ExactRay& r) {
  return {Wide(p.a) * wide(r.eye.x) + Wide(p.b) * wide(r.eye.y) + Wide(p.c) * wide(r.eye.z) + Wide(p.d),
          Wide(p.a) * wide(r.dir.x) + Wide(p.b) * wide(r.dir.y) + Wide(p.c) * wide(r.dir.z)};
}

// An exact hit: t = num / den with den > 0.
struct ExactHit {
  std::uint32_t fragment = 0;
  Wide num, den;
};

std::optional<ExactHit> exact_hit(const PlanePolygon& poly, std::uint32_t fragment, const ExactRay& r) {
  Meeting s = meeting(poly.support, r);
  if (s.slope.sign() == 0) return std::nullopt;
  if (s.slope.sign() < 0) {  // the same t with a positive denominator
    s.value = -s.value;
    s.slope = -s.slope;
  }
  const Wide num = -s.value;
  if (num.sign() < 0) return std::nullopt;  // behind the eye
  for (const GridPlane& b : poly.bounds) {
    const Meeting m = meeting(b, r);
    // B(E + t D) * den = B(E) den + (B . D) num, den > 0.
    if ((m.value * s.slope + m.slope * num).sign() < 0) return std::nullopt;
  }
  return ExactHit{fragment, num, s.slope};
}

// The sign of t_a - t_b.
int compare(const ExactHit& a, const ExactHit& b) { return (a.num * b.den - b.num * a.den).sign(); }

std::uint64_t unordered_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

struct Tally {
  std::vector<std::uint64_t> checked, violating;  // unordered pair keys
  std::uint64_t hits = 0, hit_pairs = 0, coplanar = 0, touching = 0, refused = 0;
  std::uint64_t exhaustive_rays = 0, recovered = 0;
  std::size_t compact_checked_at = kCompactAt, compact_violating_at = kCompactAt;
};

void sort_unique(std::vector<std::uint64_t>& keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

// Compacts a key list once it exceeds `at`, then moves `at` to twice what is left, so a view with
// more distinct pairs than kCompactAt is not sorted again after every batch.
void compact_if_due(std::vector<std::uint64_t>& keys, std::size_t& at) {
  if (keys.size() <= at) return;
  sort_unique(keys);
  at = std::max(kCompactAt, 2 * keys.size());
}

class ViewCheck {
 public:
  ViewCheck(const ExactTree& t, const GridPoint& eye, std::span<const std::uint32_t> order, const std::vector<Box>& boxes)
      : t_(t), eye_(eye), pos_(t.fragments.size()), boxes_(boxes) {
    for (std::uint32_t i = 0; i < order.size(); ++i) pos_[order[i]] = i;
  }

  // The exact ray toward `target` (a scene point), and its double copy for Embree; nullopt when the
  // target snaps onto the eye or beyond the grid's eye range.
  std::optional<std::pair<ExactRay, Ray>> ray_to(const Vec3& target) const {
    const auto q = snap_eye(t_.grid, target);
    if (!q || *q == eye_) return std::nullopt;
    const ExactRay r{eye_, {q->x - eye_.x, q->y - eye_.y, q->z - eye_.z}};
    const Vec3 from = t_.grid.point(eye_);
    return std::pair(r, Ray{from, t_.grid.point(*q) - from});
  }

  // `sampled`: search this ray exhaustively whatever Embree proposed; `may_search`: search it if a
  // proposal is refused.
  void check(const ExactRay& r, const Ray& approx, std::span<const Hit> proposed, bool sampled, bool may_search,
             Tally& tally) {
    hits_.clear();
    std::uint64_t refused = 0;
    for (const Hit& h : proposed) {
      if (auto e = exact_hit(t_.fragments[h.fragment], h.fragment, r)) hits_.push_back(std::move(*e));
      else ++refused;
    }
    tally.refused += refused;
    if (sampled || (refused > 0 && may_search)) recover(r, approx, proposed, tally);
    std::sort(hits_.begin(), hits_.end(), [](const ExactHit& a, const ExactHit& b) {
      const int c = compare(a, b);
      return c != 0 ? c < 0 : a.fragment < b.fragment;
    });
    tally.hits += hits_.size();
    for (std::size_t i = 0; i < hits_.size(); ++i)
      for (std::size_t j = i + 1; j < hits_.size(); ++j) {
        ++tally.hit_pairs;
        const ExactHit &nearer = hits_[i], &farther = hits_[j];
        if (compare(nearer, farther) == 0) {
          ++(same_plane(nearer.fragment, farther.fragment) ? tally.coplanar : tally.touching);
          continue;
        }
        const std::uint64_t key = unordered_key(nearer.fragment, farther.fragment);
        tally.checked.push_back(key);
        if (pos_[nearer.fragment] < pos_[farther.fragment]) tally.violating.push_back(key);
      }
  }

 private:
  // Every fragment the ray meets, decided exactly, added to the hits where Embree did not propose
  // it: a ray meeting a plane at a grazing angle can lose its candidate in floats.
  void recover(const ExactRay& r, const Ray& approx, std::span<const Hit> proposed, Tally& tally) {
    ++tally.exhaustive_rays;
    proposed_.assign(t_.fragments.size(), false);
    for (const Hit& h : proposed) proposed_[h.fragment] = true;
    for (std::uint32_t f = 0; f < t_.fragments.size(); ++f) {
      if (proposed_[f] || !ray_meets_box(approx.origin, approx.dir, boxes_[f])) continue;
      if (auto e = exact_hit(t_.fragments[f], f, r)) {
        hits_.push_back(std::move(*e));
        ++tally.recovered;
      }
    }
  }

  bool same_plane(std::uint32_t a, std::uint32_t b) const {
    return PlanePool::coplanar(t_.tree.fragment_plane[a], t_.tree.fragment_plane[b]);
  }

  const ExactTree& t_;
  GridPoint eye_;
  std::vector<std::uint32_t> pos_;
  std::vector<ExactHit> hits_;
  std::vector<bool> proposed_;
  const std::vector<Box>& boxes_;
};

// One view: its rays in batches over the threads; counts are sums and set sizes, the same on any
// thread count.
void check_view(const ExactTree& t, const EmbreeScene& scene, const std::vector<Polygon>& fragments,
                const GridPoint& eye, const ValidationSettings& settings, ExactValidationReport& out) {
  const std::vector<std::uint32_t> order = exact_visibility_order(t, eye, Order::BackToFront);
  const Vec3 eye_point = t.grid.point(eye);
  const double reach = std::max(t.tree.bounds.diagonal(), 1e-300);
  std::vector<ExactRay> exact;
  std::vector<Ray> rays;
  const std::vector<Box> boxes = recover_boxes(fragments, t.tree.bounds);
  ViewCheck probe(t, eye, order, boxes);
  for (const Ray& r : validation_rays(fragments, t.tree.bounds, eye_point, settings))
    if (auto pair = probe.ray_to(eye_point + r.dir * (reach / std::max(length(r.dir), 1e-300)))) {
      exact.push_back(pair->first);
      rays.push_back(pair->second);
    }
  Tally all;
  // Each kind of search spends at most about kRecoverBudget fragment tests on the view.
  const double thinning = std::ceil(static_cast<double>(rays.size()) * static_cast<double>(fragments.size()) / kRecoverBudget);
  const auto stride = static_cast<std::size_t>(std::max(1.0, thinning));
  const auto sample_every = std::max(kExhaustiveEvery, stride);
  const auto batches = static_cast<std::int64_t>((rays.size() + kRaysPerBatch - 1) / kRaysPerBatch);
#pragma omp parallel
  {
    Tally mine;
    ViewCheck view(t, eye, order, boxes);
    HitBatch batch;
#pragma omp for schedule(dynamic, 1) nowait
    for (std::int64_t b = 0; b < batches; ++b) {
      const std::size_t first = static_cast<std::size_t>(b) * kRaysPerBatch;
      const std::size_t count = std::min(kRaysPerBatch, rays.size() - first);
      scene.all_hits(std::span<const Ray>(rays).subspan(first, count), batch);
      for (std::size_t i = 0; i < count; ++i)
        view.check(exact[first + i], rays[first + i], batch.of(i), (first + i) % sample_every == 0,
                   (first + i) % stride == 0, mine);
      compact_if_due(mine.checked, mine.compact_checked_at);
      compact_if_due(mine.violating, mine.compact_violating_at);
    }
    sort_unique(mine.checked);
    sort_unique(mine.violating);
#pragma omp critical(bsp_exact_order_merge)
    {
      all.checked.insert(all.checked.end(), mine.checked.begin(), mine.checked.end());
      all.violating.insert(all.violating.end(), mine.violating.begin(), mine.violating.end());
      all.hits += mine.hits;
      all.hit_pairs += mine.hit_pairs;
      all.coplanar += mine.coplanar;
      all.touching += mine.touching;
      all.refused += mine.refused;
      all.exhaustive_rays += mine.exhaustive_rays;
      all.recovered += mine.recovered;
    }
  }
  sort_unique(all.checked);
  sort_unique(all.violating);
  ValidationReport& r = out.report;
  const int view = r.views++;
  r.rays += rays.size();
  r.hits += all.hits;
  r.hit_pairs += all.hit_pairs;
  r.pairs_checked += all.checked.size();
  r.violations += all.violating.size();
  r.ties_coplanar += all.coplanar;
  r.ties_edge += all.touching;
  out.refused += all.refused;
  out.exhaustive_rays += all.exhaustive_rays;
  out.recovered += all.recovered;
  for (std::uint64_t k : all.violating) {
    if (r.first_problems.size() >= OrderCheck::kMaxReported) break;
    r.first_problems.push_back("view " + std::to_string(view) + ": fragments " + std::to_string(k >> 32) + " and " +
                               std::to_string(k & 0xffffffffu) + " are drawn in the wrong order");
  }
}

}  // namespace

ExactValidationReport validate_exact_tree(const ExactTree& t, const ValidationSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  ExactValidationReport out;
  out.report.fragments = t.fragments.size();
  const std::vector<Polygon> fragments = t.tree.fragments.to_polygons();
  const EmbreeScene scene(fragments, t.tree.tol.plane_eps);
  for (const Vec3& e : validation_eyes(t.tree.bounds, settings.views)) {
    const auto eye = snap_eye(t.grid, e);
    if (!eye) {
      ++out.eyes_beyond;
      continue;
    }
    check_view(t, scene, fragments, *eye, settings, out);
  }
  out.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.report.rays_per_second = out.report.seconds > 0 ? static_cast<double>(out.report.rays) / out.report.seconds : 0;
  return out;
}

nlohmann::json to_json(const ExactValidationReport& r) {
  nlohmann::json out = to_json(r.report);
  out["refused_hits"] = r.refused;
  out["exhaustive_rays"] = r.exhaustive_rays;
  out["recovered_hits"] = r.recovered;
  out["eyes_beyond"] = r.eyes_beyond;
  return out;
}

}  // namespace bsp
