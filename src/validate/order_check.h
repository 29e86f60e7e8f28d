#pragma once
// Checking back-to-front visibility orders against Embree [Wald2014].
//
// The rule: along any ray from the eye, a fragment hit nearer must be drawn after every fragment
// hit farther away. For each ray, every pair of hits that is not a tie (embree_scene.h: coplanar,
// meeting where the two fragments touch, or one passed within the boundary slack, unless a ray
// turned just enough to meet it still meets the other: overlap_nearby) is checked; a pair drawn
// in the wrong order is a violation. Pairs are counted as distinct unordered fragment pairs, so one wrongly ordered pair
// seen by many rays counts once per view; hit pairs and ties are counted per ray.
//
// Speed: the rays are sorted by direction and cast in batches of Embree packets; per ray, the hits
// are decided in double and every pair judged; a thread keeps its buffers from batch to batch.
// Deterministic: batches are cast in parallel (tracing a committed scene is thread-safe), but every
// count is a sum or a set size, the same on any thread count and in any ray order.
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "tree/tree.h"
#include "validate/embree_scene.h"
#include "validate/view_rays.h"

namespace bsp {

struct OrderCheck {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;           // fragment hits over all rays
  std::uint64_t hit_pairs = 0;      // pairs of hits on one ray, summed over rays
  std::uint64_t pairs_checked = 0;  // distinct unordered fragment pairs compared on some ray
  std::uint64_t violations = 0;     // distinct unordered fragment pairs drawn in the wrong order
  std::uint64_t ties_coplanar = 0;  // hit pairs not judged because their planes coincide
  std::uint64_t ties_edge = 0;      // hit pairs not judged because the ray meets them where they touch
  std::uint64_t ties_boundary = 0;  // hit pairs not judged because the ray passes one within the boundary slack
  // Up to kMaxReported violating pairs as (nearer, farther) fragment ids, smallest first.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> examples;

  static constexpr std::size_t kMaxReported = 10;
};

// `back_to_front` must hold every fragment of the scene exactly once; throws InputError otherwise.
OrderCheck check_order(const EmbreeScene& scene, std::span<const Ray> rays,
                       std::span<const std::uint32_t> back_to_front);

struct ValidationReport {
  int views = 0;
  std::uint64_t fragments = 0;
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;
  std::uint64_t hit_pairs = 0;      // as OrderCheck's, summed over views
  std::uint64_t pairs_checked = 0;  // summed over views
  std::uint64_t violations = 0;     // summed over views
  std::uint64_t ties_coplanar = 0;
  std::uint64_t ties_edge = 0;
  std::uint64_t ties_boundary = 0;
  double plane_eps = 0.0;        // the tolerance the ties were judged with, world units
  double seconds = 0.0;          // wall time, Embree scene build included
  double rays_per_second = 0.0;  // rays / time spent making, casting and checking them
  std::vector<std::string> first_problems;  // up to OrderCheck::kMaxReported, for messages

  std::uint64_t ties() const { return ties_coplanar + ties_edge + ties_boundary; }
  bool ok() const { return violations == 0; }
};

// Every view of validation_eyes(tree.bounds, settings.views), each checking the tree's own
// back-to-front traversal from that eye.
ValidationReport validate_tree(const Tree& tree, const ValidationSettings& settings = {});

// A 2D tree (segments, geometry/segment2.h) from eyes in its plane: each segment extruded to a wall
// from z = 0 to the scene's diagonal (extruded()), each eye raised to half that height, and its
// back-to-front order checked like a 3D one. The order of walls is the order of their segments,
// since every partition plane of a 2D tree is vertical.
ValidationReport validate_segment_tree(const Tree& tree, std::span<const Vec3> eyes, const ValidationSettings& settings = {});

// One eye and an arbitrary order of arbitrary polygons (a depth sort, an order read from a file).
// The ray set is validation_rays over the polygons' bounding box.
ValidationReport validate_order(std::span<const Polygon> polys, const Vec3& eye,
                                std::span<const std::uint32_t> order, const ValidationSettings& settings = {});

nlohmann::json to_json(const ValidationReport& report);

}  // namespace bsp
