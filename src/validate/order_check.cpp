#include "validate/order_check.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "geometry/segment2.h"
#include "tree/traverse.h"

namespace bsp {

namespace {

// A thread's pair keys are compacted (sorted, deduplicated) once they exceed this many, which
// bounds memory on rays that cross many fragments.
constexpr std::size_t kCompactAt = std::size_t{1} << 22;
// Rays a thread casts at once: a few Embree packets, and the unit of the dynamic schedule.
constexpr std::size_t kRaysPerBatch = 64;

std::uint64_t ordered_key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; }
std::uint64_t unordered_key(std::uint32_t a, std::uint32_t b) { return ordered_key(std::min(a, b), std::max(a, b)); }

// LSD radix sort in 16-bit digits, then deduplication: the key lists run to millions per view, and
// this is several times faster than a comparison sort there. A digit every key shares is skipped
// (the high digits of fragment ids below 65536).
void sort_unique(std::vector<std::uint64_t>& keys) {
  constexpr int kDigitBits = 16;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  std::vector<std::uint64_t> tmp(keys.size());
  std::vector<std::size_t> start(kBuckets + 1);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    std::fill(start.begin(), start.end(), 0);
    for (std::uint64_t k : keys) ++start[((k >> shift) & (kBuckets - 1)) + 1];
    if (std::find(start.begin(), start.end(), keys.size()) != start.end()) continue;
    for (std::size_t b = 1; b <= kBuckets; ++b) start[b] += start[b - 1];
    for (std::uint64_t k : keys) tmp[start[(k >> shift) & (kBuckets - 1)]++] = k;
    keys.swap(tmp);
  }
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

// pos[f] = place of fragment f in the order.
std::vector<std::uint32_t> positions(std::span<const std::uint32_t> order, std::size_t n) {
  if (order.size() != n)
    throw InputError("the order has " + std::to_string(order.size()) + " entries but there are " + std::to_string(n) +
                     " fragments");
  std::vector<std::uint32_t> pos(n, kNull);
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    const std::uint32_t f = order[i];
    if (f >= n) throw InputError("the order names fragment " + std::to_string(f) + " of " + std::to_string(n));
    if (pos[f] != kNull) throw InputError("the order lists fragment " + std::to_string(f) + " twice");
    pos[f] = i;
  }
  return pos;
}

// Sorts and deduplicates `keys` once they exceed `at`, then moves `at` to twice what is left: a view
// with more distinct pairs than kCompactAt (a million fragments have millions) would otherwise sort
// the whole list again after every batch.
void compact_if_due(std::vector<std::uint64_t>& keys, std::size_t& at) {
  if (keys.size() <= at) return;
  sort_unique(keys);
  at = std::max(kCompactAt, 2 * keys.size());
}

// Neighbouring rays meet the same pairs (on random-triangles 2000, 9 hit pairs in 10 repeat a pair
// already seen), so a small direct-mapped table of recently added keys drops most repeats before they
// reach the key list. It only drops exact repeats: the set of keys is the same without it.
class RecentKeys {
 public:
  // True when `key` is in its slot; otherwise it takes the slot.
  bool seen(std::uint64_t key) {
    std::uint64_t& s = slot_[(key * kMix) >> (64 - kSlotBits)];
    if (s == key) return true;
    s = key;
    return false;
  }

 private:
  static constexpr int kSlotBits = 12;
  static constexpr std::uint64_t kMix = 0x9e3779b97f4a7c15;  // Fibonacci hashing
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // the key of (kNull, kNull), never a pair
  std::vector<std::uint64_t> slot_ = std::vector<std::uint64_t>(std::size_t{1} << kSlotBits, kEmpty);
};

// What one thread saw.
struct Tally {
  RecentKeys recent;                     // of `checked`
  std::vector<std::uint64_t> checked;    // unordered keys
  std::vector<std::uint64_t> violating;  // ordered keys (nearer, farther)
  std::size_t compact_checked_at = kCompactAt, compact_violating_at = kCompactAt;
  std::uint64_t hits = 0, hit_pairs = 0, ties_coplanar = 0, ties_edge = 0, ties_boundary = 0;

  // Merges another thread's tally; both key lists must be sorted and free of repeats.
  void add(const Tally& o) {
    merge_unique(checked, o.checked);
    merge_unique(violating, o.violating);
    hits += o.hits;
    hit_pairs += o.hit_pairs;
    ties_coplanar += o.ties_coplanar;
    ties_edge += o.ties_edge;
    ties_boundary += o.ties_boundary;
  }

  static void merge_unique(std::vector<std::uint64_t>& into, const std::vector<std::uint64_t>& from) {
    std::vector<std::uint64_t> merged;
    merged.reserve(into.size() + from.size());
    std::set_union(into.begin(), into.end(), from.begin(), from.end(), std::back_inserter(merged));
    into.swap(merged);
  }
};

// Counts a tie by its reason; false when the pair is to be judged.
bool count_tie(TieReason reason, Tally& tally) {
  switch (reason) {
    case TieReason::None: return false;
    case TieReason::Coplanar: ++tally.ties_coplanar; break;
    case TieReason::Edge: ++tally.ties_edge; break;
    case TieReason::Boundary: ++tally.ties_boundary; break;
  }
  return true;
}

// Every pair of hits on one ray that is not a tie (embree_scene.h): the nearer fragment must come
// later in the order.
void check_ray(const EmbreeScene& scene, const Ray& ray, std::span<const Hit> hits,
               const std::vector<std::uint32_t>& pos, Tally& tally) {
  tally.hits += hits.size();
  tally.hit_pairs += hits.size() * (hits.size() - (hits.empty() ? 0 : 1)) / 2;
  for (std::size_t i = 0; i < hits.size(); ++i)
    for (std::size_t j = i + 1; j < hits.size(); ++j) {
      TieReason reason = scene.tie_reason(ray, hits[i], hits[j]);
      if (reason == TieReason::Boundary && scene.overlap_nearby(hits[i], hits[j])) reason = TieReason::None;
      if (count_tie(reason, tally)) continue;
      const std::uint32_t nearer = hits[i].fragment, farther = hits[j].fragment;
      const std::uint64_t key = unordered_key(nearer, farther);
      if (!tally.recent.seen(key)) tally.checked.push_back(key);
      if (pos[nearer] < pos[farther]) tally.violating.push_back(ordered_key(nearer, farther));
    }
}

// The rays order[first, first + kRaysPerBatch) of `all`, copied into `rays` (a thread's reused buffer).
void check_batch(const EmbreeScene& scene, std::span<const Ray> all, const std::vector<std::uint32_t>& order,
                 std::size_t first, const std::vector<std::uint32_t>& pos, std::vector<Ray>& rays, HitBatch& batch,
                 Tally& tally) {
  rays.clear();
  for (std::size_t i = first; i < std::min(order.size(), first + kRaysPerBatch); ++i) rays.push_back(all[order[i]]);
  scene.all_hits(rays, batch);
  for (std::size_t r = 0; r < rays.size(); ++r) check_ray(scene, rays[r], batch.of(r), pos, tally);
  compact_if_due(tally.checked, tally.compact_checked_at);
  compact_if_due(tally.violating, tally.compact_violating_at);
}

// Spreads the low 16 bits of x to the even bits.
std::uint32_t spread_bits(std::uint32_t x) {
  x &= 0xffff;
  x = (x | (x << 8)) & 0x00ff00ff;
  x = (x | (x << 4)) & 0x0f0f0f0f;
  x = (x | (x << 2)) & 0x33333333;
  x = (x | (x << 1)) & 0x55555555;
  return x;
}

// A Morton code [Morton1966] of the ray's direction on the octahedral map of the sphere
// [Meyer2010]: rays with near codes point nearly the same way.
std::uint32_t direction_code(const Vec3& d) {
  const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
  if (!(l1 > 0.0) || !std::isfinite(l1)) return 0;
  double u = d.x / l1, v = d.y / l1;
  if (d.z < 0.0) {
    const double fu = (1.0 - std::abs(v)) * (u < 0.0 ? -1.0 : 1.0);
    v = (1.0 - std::abs(u)) * (v < 0.0 ? -1.0 : 1.0);
    u = fu;
  }
  const auto quantise = [](double c) { return static_cast<std::uint32_t>(std::clamp((c + 1.0) * 32767.5, 0.0, 65535.0)); };
  return spread_bits(quantise(u)) | (spread_bits(quantise(v)) << 1);
}

std::array<double, 6> coordinates(const Ray& r) {
  return {r.dir.x, r.dir.y, r.dir.z, r.origin.x, r.origin.y, r.origin.z};
}

// The indices of the rays in the order of their directions' codes. Embree traces a packet of rays
// that point nearly the same way far faster than a scattered one, and the rays of a view (aimed at
// fragments in tree order, then a pixel grid) come scattered. Equal codes are ordered by the rays'
// coordinates, so the packets, and so every count, do not depend on the order the rays came in.
std::vector<std::uint32_t> coherent_order(std::span<const Ray> rays) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> code(rays.size());
  for (std::uint32_t i = 0; i < rays.size(); ++i) code[i] = {direction_code(rays[i].dir), i};
  std::sort(code.begin(), code.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    return coordinates(rays[a.second]) < coordinates(rays[b.second]);
  });
  std::vector<std::uint32_t> order;
  order.reserve(rays.size());
  for (const auto& c : code) order.push_back(c.second);
  return order;
}

OrderCheck summarise(const Tally& all, std::uint64_t rays) {
  OrderCheck out;
  out.rays = rays;
  out.hits = all.hits;
  out.hit_pairs = all.hit_pairs;
  out.ties_coplanar = all.ties_coplanar;
  out.ties_edge = all.ties_edge;
  out.ties_boundary = all.ties_boundary;
  out.pairs_checked = all.checked.size();
  for (std::size_t i = 0; i < all.violating.size() && i < OrderCheck::kMaxReported; ++i)
    out.examples.emplace_back(static_cast<std::uint32_t>(all.violating[i] >> 32),
                              static_cast<std::uint32_t>(all.violating[i]));
  std::vector<std::uint64_t> unordered;
  for (std::uint64_t k : all.violating)
    unordered.push_back(unordered_key(static_cast<std::uint32_t>(k >> 32), static_cast<std::uint32_t>(k)));
  sort_unique(unordered);
  out.violations = unordered.size();
  return out;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void set_timing(ValidationReport& r, Clock::time_point start, Clock::time_point cast_start) {
  const double cast_seconds = seconds_since(cast_start);
  r.seconds = seconds_since(start);
  r.rays_per_second = cast_seconds > 0.0 ? static_cast<double>(r.rays) / cast_seconds : 0.0;
}

// Adds one view's check to the report.
void accumulate(ValidationReport& r, const OrderCheck& c, int view) {
  ++r.views;
  r.rays += c.rays;
  r.hits += c.hits;
  r.pairs_checked += c.pairs_checked;
  r.violations += c.violations;
  r.hit_pairs += c.hit_pairs;
  r.ties_coplanar += c.ties_coplanar;
  r.ties_edge += c.ties_edge;
  r.ties_boundary += c.ties_boundary;
  for (const auto& [nearer, farther] : c.examples) {
    if (r.first_problems.size() >= OrderCheck::kMaxReported) break;
    r.first_problems.push_back("view " + std::to_string(view) + ": fragment " + std::to_string(nearer) +
                               " is hit nearer than fragment " + std::to_string(farther) + " but drawn before it");
  }
}

}  // namespace

OrderCheck check_order(const EmbreeScene& scene, std::span<const Ray> rays,
                       std::span<const std::uint32_t> back_to_front) {
  const std::vector<std::uint32_t> pos = positions(back_to_front, scene.fragment_count());
  const std::vector<std::uint32_t> order = coherent_order(rays);
  Tally all;
  const auto batches = static_cast<std::int64_t>((rays.size() + kRaysPerBatch - 1) / kRaysPerBatch);
#pragma omp parallel
  {
    Tally mine;
    std::vector<Ray> batch_rays;
    HitBatch batch;
#pragma omp for schedule(dynamic, 1) nowait
    for (std::int64_t b = 0; b < batches; ++b) {
      check_batch(scene, rays, order, static_cast<std::size_t>(b) * kRaysPerBatch, pos, batch_rays, batch, mine);
    }
    // Sorting here runs on every thread; the merge below is linear.
    sort_unique(mine.checked);
    sort_unique(mine.violating);
#pragma omp critical(bsp_order_check_merge)
    all.add(mine);
  }
  return summarise(all, rays.size());
}

ValidationReport validate_tree(const Tree& tree, const ValidationSettings& settings) {
  const auto start = Clock::now();
  ValidationReport r;
  const std::vector<Polygon> fragments = tree.fragments.to_polygons();
  const EmbreeScene scene(fragments, tree.tol.plane_eps);
  r.fragments = tree.fragments.size();
  r.plane_eps = scene.plane_eps();
  const auto cast_start = Clock::now();
  const std::vector<Vec3> eyes = validation_eyes(tree.bounds, settings.views);
  for (std::size_t v = 0; v < eyes.size(); ++v) {
    const auto order = visibility_order(tree, eyes[v], Order::BackToFront);
    const auto rays = validation_rays(fragments, tree.bounds, eyes[v], settings);
    accumulate(r, check_order(scene, rays, order), static_cast<int>(v));
  }
  set_timing(r, start, cast_start);
  return r;
}

ValidationReport validate_segment_tree(const Tree& tree, std::span<const Vec3> eyes, const ValidationSettings& settings) {
  const auto start = Clock::now();
  ValidationReport r;
  const double height = std::max(tree.bounds.diagonal(), 1e-9);
  const std::vector<Polygon> walls = extruded(tree.fragments.to_polygons(), height);
  Box box = tree.bounds;
  box.add(Vec3{box.lo.x, box.lo.y, height});
  const EmbreeScene scene(walls, tree.tol.plane_eps);
  r.fragments = tree.fragments.size();
  r.plane_eps = scene.plane_eps();
  const auto cast_start = Clock::now();
  for (std::size_t v = 0; v < eyes.size(); ++v) {
    const Vec3 eye{eyes[v].x, eyes[v].y, 0.5 * height};
    const auto order = visibility_order(tree, eye, Order::BackToFront);
    const auto rays = validation_rays(walls, box, eye, settings);
    accumulate(r, check_order(scene, rays, order), static_cast<int>(v));
  }
  set_timing(r, start, cast_start);
  return r;
}

ValidationReport validate_order(std::span<const Polygon> polys, const Vec3& eye,
                                std::span<const std::uint32_t> order, const ValidationSettings& settings) {
  const auto start = Clock::now();
  ValidationReport r;
  const EmbreeScene scene(polys);
  r.fragments = polys.size();
  r.plane_eps = scene.plane_eps();
  Box box;
  for (const auto& p : polys)
    for (const auto& v : p.verts) box.add(v.p);
  const auto cast_start = Clock::now();
  const auto rays = validation_rays(polys, box, eye, settings);
  accumulate(r, check_order(scene, rays, order), 0);
  set_timing(r, start, cast_start);
  return r;
}

nlohmann::json to_json(const ValidationReport& r) {
  return {{"views", r.views},
          {"fragments", r.fragments},
          {"rays", r.rays},
          {"hits", r.hits},
          {"hit_pairs", r.hit_pairs},
          {"pairs_checked", r.pairs_checked},
          {"violations", r.violations},
          {"ties", r.ties()},
          {"ties_coplanar", r.ties_coplanar},
          {"ties_edge", r.ties_edge},
          {"ties_boundary", r.ties_boundary},
          {"plane_eps", r.plane_eps},
          {"seconds", r.seconds},
          {"rays_per_second", r.rays_per_second},
          {"first_problems", r.first_problems}};
}

}  // namespace bsp
