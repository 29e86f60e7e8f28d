#pragma once
// Candidate planes for the autopartition heuristics and the counts they are scored by: which of the
// node's fragments to try as the splitting plane, and how many fragments fall in front of, behind,
// on and across each candidate. Shared so that every scorer counts the same way.
#include <cstdint>
#include <span>
#include <vector>

#include "common/params.h"
#include "common/rng.h"
#include "split/splitter.h"

namespace bsp {

// A plane counts as axis-aligned when one component of its unit normal is within this of ±1. Quake's
// qbsp types a plane axial when its normal is exactly an axis (near-axial normals are snapped when
// the map is read); this tolerance stands in for that snapping and for the rounding of a Newell
// normal computed from axis-aligned vertices, which is a few ulps.
inline constexpr double kAxialNormalTolerance = 1e-9;

bool is_axial(const Plane& p);

// The `candidates` parameter shared by the sampling heuristics: k = 0 means every distinct plane.
ParamSpec candidates_param(double default_k, const std::string& doc_suffix);

// One fragment per distinct pooled plane among ctx.ids (a plane and its flip count as one, since
// they make the same partition), the first in ids order. When 0 < k < that number, k of them drawn
// uniformly without replacement from `rng`; the result is in ids order either way, so ties between
// equal scores go to the fragment that comes first in the node's set. Sampling over distinct planes
// rather than fragments keeps a plane shared by many coplanar fragments from being scored twice.
std::vector<std::uint32_t> candidate_fragments(const SplitContext& ctx, std::size_t k, Rng& rng);

// The node's fragments classified against fragment `id`'s plane (the fragment itself counts as
// coplanar).
SideCounts count_against(const SplitContext& ctx, std::uint32_t id);

// The candidate whose cost is smallest; ties go to the earliest. `cost(id, counts)` returns any
// type ordered by `<` (a number, or a pair for lexicographic tie-breaking).
template <class Cost>
std::uint32_t argmin_candidate(const SplitContext& ctx, std::span<const std::uint32_t> candidates, Cost cost) {
  std::uint32_t best = candidates.front();
  auto best_cost = cost(best, count_against(ctx, best));
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const auto c = cost(candidates[i], count_against(ctx, candidates[i]));
    if (c < best_cost) {
      best_cost = c;
      best = candidates[i];
    }
  }
  return best;
}

}  // namespace bsp
