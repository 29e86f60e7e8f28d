#pragma once
// Checking an exact tree's back-to-front orders with every decision about a proposed hit exact
// (tree/exact_build.h).
//
// The eyes are validation_eyes snapped to the scene's grid, and every ray runs from its eye to a
// grid point (its direction's point one scene diagonal away, snapped), so a ray is E + t D with
// integer E and D. Embree (validate/embree_scene.h) proposes the fragments each ray may meet, from
// the tree's view in doubles; each proposal is then decided exactly on the fragment's planes:
//  - the ray meets the support S (normal A) at t = -S(E) / (A . D) when A . D != 0 (a ray in or
//    parallel to the plane meets no point of the fragment's interior and is not a hit);
//  - that point is in the fragment when every bound B has B(E) (A . D) - (B . D) S(E) of the sign
//    of A . D or zero (the boundary counts as inside);
//  - two hits are ordered by comparing -S_f(E) / (A_f . D) with -S_g(E) / (A_g . D) by cross
//    multiplication. Equal parameters are the only ties: the same point of the ray on two
//    fragments, either coplanar (the same support plane: overlapping there, or two pieces sharing
//    an edge the ray crosses) or touching there.
// A fragment the ray meets that Embree does not propose (at a grazing angle a candidate can be lost
// in floats) is recovered by an exhaustive search, as the occlusion check does: on rays where a
// proposal was refused (the sign of a ray grazing a boundary) and on every 64th ray of a view (both
// thinned to every k-th where rays times fragments exceed a budget of fragment tests per view),
// every fragment is tested exactly and the hits Embree missed join the ray's (`recovered`).
// Widths: |E|, |D| < 2^53 (tree/exact_traverse.h: kEyeBits), coefficients below 2^83 (normals)
// and 2^125 (offsets), so S(E) and A . D are below 2^138 and their cross products below 2^277:
// WideInt<5> (320 bits) holds every value exactly.
//
// Proposals Embree's double-precision test accepted that the exact test refuses are counted
// (`refused`): hits at a boundary, within the double test's slack, that exactness decides outside.
#include <cstdint>
#include <nlohmann/json_fwd.hpp>

#include "tree/exact_build.h"
#include "validate/order_check.h"
#include "validate/view_rays.h"

namespace bsp {

struct ExactValidationReport {
  // As a float validation's, with ties_coplanar counting exact overlaps, ties_edge exact touching,
  // ties_boundary always 0 and plane_eps 0.
  ValidationReport report;
  std::uint64_t refused = 0;  // proposals the double test accepted and the exact test refuses
  std::uint64_t exhaustive_rays = 0;  // rays searched exhaustively (every fragment tested exactly)
  std::uint64_t recovered = 0;        // exact hits on those rays that Embree did not propose
  std::uint64_t eyes_beyond = 0;  // eyes beyond the grid's eye range, not checked
};

// Every view of validation_eyes(tree.tree.bounds, settings.views), each checking the tree's exact
// back-to-front order from that eye, snapped to the grid.
ExactValidationReport validate_exact_tree(const ExactTree& tree, const ValidationSettings& settings = {});

nlohmann::json to_json(const ExactValidationReport& r);

}  // namespace bsp
