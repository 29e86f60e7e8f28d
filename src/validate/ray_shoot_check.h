#pragma once
// Checking the tree's ray shooting (metrics/ray_shoot.h) against Embree's first hit, ray by ray:
// a second correctness check of a tree, independent of the visibility-order check.
//
// Verdict per ray, first that applies:
//  - agree: both miss, or both name the same fragment;
//  - tie: the two hits lie within tie_tolerance() of each other along the ray (embree_scene.h);
//  - grazing: the ray passes within tie_tolerance() of the boundary of the fragment of the nearer
//    of the two claimed hits (distance between the ray's line and the fragment's edges), so a
//    float rounding of the ray or the vertices can decide whether it meets that fragment: rays
//    past an edge, or nearly parallel to a small fragment's plane, where Embree's float test
//    shifts the hit point by its error divided by the sine of the incidence angle;
//  - mismatch: anything else, e.g. the walk skipped the subtree holding the nearest fragment.
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

enum class HitVerdict : std::uint8_t { Agree, Tie, Grazing, Mismatch };

// `fragments` are those both hits index.
HitVerdict judge_first_hits(const std::optional<Hit>& bsp, const std::optional<Hit>& embree, const Ray& ray,
                            std::span<const Polygon> fragments, double tie);

struct RayShootCheck {
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;        // rays on which Embree reports a hit
  std::uint64_t ties = 0;
  std::uint64_t grazing = 0;
  std::uint64_t mismatches = 0;
  std::vector<std::string> first_problems;  // up to kMaxReported, for messages

  static constexpr std::size_t kMaxReported = 10;
  bool ok() const { return mismatches == 0; }
};

// `embree` must be built from tree.fragments.
RayShootCheck check_ray_shooting(const Tree& tree, const EmbreeScene& embree, std::span<const Ray> rays);
// The rays of validate_tree: validation_rays from every eye of validation_eyes(tree.bounds, views).
RayShootCheck check_ray_shooting(const Tree& tree, const ValidationSettings& settings = {});

nlohmann::json to_json(const RayShootCheck& check);

}  // namespace bsp
