#pragma once
// Checking the tree's ray shooting (tree/ray_shoot.h) against Embree's first hit, ray by ray:
// a second correctness check of a tree, independent of the visibility-order check.
//
// Verdict per ray: agree when the walk and Embree both miss or name the same fragment. Otherwise
// Embree's answer is replaced by the exhaustive double-precision search (first_hit_exhaustive),
// since Embree's float candidates can miss a fragment met at a grazing angle, and the walk's
// answer is judged against that: agree when both miss or name the same fragment, a tie when the
// two fragments' hits are tied by the order check's rule (EmbreeScene::tie_reason), counted by
// reason; anything else is a mismatch, e.g. the walk
// skipped the subtree holding the nearest fragment, or it claims a fragment the ray does not meet.
// Nothing is excused: a disagreement is a tie by that rule or a failure.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "tree/tree.h"
#include "validate/embree_scene.h"
#include "validate/view_rays.h"

namespace bsp {

enum class HitVerdict : std::uint8_t { Agree, AgreeExhaustive, TieCoplanar, TieEdge, TieBoundary, Mismatch };

// `scene` holds the fragments both hits index; `embree` is its first hit on the ray.
HitVerdict judge_first_hits(const std::optional<RayHit>& bsp, const std::optional<Hit>& embree, const Ray& ray,
                            const EmbreeScene& scene);

struct RayShootCheck {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;        // rays on which Embree reports a hit
  std::uint64_t exhaustive = 0;  // rays where Embree disagreed and the exhaustive search judged
  std::uint64_t ties_coplanar = 0;
  std::uint64_t ties_edge = 0;
  std::uint64_t ties_boundary = 0;
  std::uint64_t mismatches = 0;
  std::vector<std::string> first_problems;  // up to kMaxReported, for messages

  static constexpr std::size_t kMaxReported = 10;
  std::uint64_t ties() const { return ties_coplanar + ties_edge + ties_boundary; }
  bool ok() const { return mismatches == 0; }
};

// `embree` must be built from tree.fragments.
RayShootCheck check_ray_shooting(const Tree& tree, const EmbreeScene& embree, std::span<const Ray> rays);
// The rays of validate_tree: validation_rays from every eye of validation_eyes(tree.bounds, views).
RayShootCheck check_ray_shooting(const Tree& tree, const ValidationSettings& settings = {});

nlohmann::json to_json(const RayShootCheck& check);

}  // namespace bsp
