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

// Default k of the sampling scorers (weighted and its presets, balanced, min-relation). Scoring
// every plane costs O(m²) per node, so their builds grew as n^1.4–1.65; a fixed number of sampled
// candidates per node keeps them near n log n ([Chrysanthou §7]: "select a few candidate polygons at
// each iteration"). Measured with `weighted` at n = 10^4 (README, "Choosing k"): 32 candidates
// leave 2–6% more fragments than scoring every plane at a tenth of the build time or less; 16
// leave 5–18% more, 8 up to 21%.
inline constexpr std::uint64_t kSampledCandidates = 32;
// Note for presets whose source scores every candidate.
inline constexpr const char* kSourceScoresAll = "; its source scores all (candidates = 0 reproduces it)";

// A stamp per pooled plane pair, so finding the node's distinct planes takes one pass over its
// fragments instead of a sort.
class PlaneMarks {
 public:
  // Starts a pass over a pool of `pairs` plane pairs: every pair is unseen again.
  void begin(std::size_t pairs);
  // True the first time the pair is seen in this pass.
  bool first_sight(std::uint32_t pair) {
    if (stamp_[pair] == pass_) return false;
    stamp_[pair] = pass_;
    return true;
  }

 private:
  std::vector<std::uint32_t> stamp_;
  std::uint32_t pass_ = 0;
};

// The scratch of candidate_fragments and SideCounter. Each splitter owns one, so that choosing a
// node's plane allocates nothing unless the counted fragments are sampled: the arrays keep their
// capacity from node to node (most nodes are small, and allocating a few arrays for each cost more
// than counting its sides). Scratch, not state: a copy (a task's clone of the splitter) starts empty.
struct CandidateScratch {
  CandidateScratch() = default;
  CandidateScratch(const CandidateScratch&) {}
  CandidateScratch& operator=(const CandidateScratch&) { return *this; }

  PlaneMarks marks;
  std::vector<std::uint32_t> positions, candidates;  // candidate_fragments'
  std::vector<Plane> planes;                         // SideCounter's: the candidates' planes
  std::vector<std::uint32_t> pooled;                 // the same as pool indices, in an exact build
  std::vector<SideCounts> counts;
};

// One fragment per distinct pooled plane among ctx.ids (a plane and its flip count as one, since
// they make the same partition), the first in ids order. When 0 < k < that number, k of them drawn
// uniformly without replacement from `rng`; the result is in ids order either way, so ties between
// equal scores go to the fragment that comes first in the node's set. Sampling over distinct planes
// rather than fragments keeps a plane shared by many coplanar fragments from being scored twice.
// The result lives in scratch.candidates until the next call.
std::span<const std::uint32_t> candidate_fragments(const SplitContext& ctx, std::size_t k, Rng& rng,
                                                   CandidateScratch& scratch);

// The `sample` parameter: s = 0 counts every fragment of the node.
ParamSpec sample_param(double default_s);

// Counts of the node's fragments on each side of a candidate's plane, taken over all of them or, when
// 0 < s < m, over s of them drawn once per node uniformly without replacement (Crystal Space's
// estimate): every candidate of the node is counted over the same fragments, so their comparison
// is not blurred by different draws. A node then costs O(k·s + m + s log s) instead of O(k·m).
class SideCounter {
 public:
  SideCounter(const SplitContext& ctx, std::size_t s, Rng& rng, CandidateScratch& scratch);
  // Each candidate fragment's plane against the counted fragments (a candidate counts as coplanar
  // with itself when counted), all in one pass over them (FragmentStore::count_sides). The counts
  // live in the scratch until the next call.
  std::span<const SideCounts> operator()(std::span<const std::uint32_t> candidates) const;
  // m / (fragments counted): multiplies a count into an estimate for the whole node.
  double scale() const { return scale_; }

 private:
  const SplitContext& ctx_;
  CandidateScratch& scratch_;
  std::vector<std::uint32_t> sampled_;  // empty when every fragment is counted
  double scale_ = 1.0;
};

// The candidate whose cost is smallest; ties go to the earliest. `cost(id, counts)` returns any
// type ordered by `<` (a number, or a pair for lexicographic tie-breaking).
template <class Cost>
std::uint32_t argmin_candidate(const SideCounter& count, std::span<const std::uint32_t> candidates, Cost cost) {
  const std::span<const SideCounts> counts = count(candidates);
  std::uint32_t best = candidates.front();
  auto best_cost = cost(best, counts.front());
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const auto c = cost(candidates[i], counts[i]);
    if (c < best_cost) {
      best_cost = c;
      best = candidates[i];
    }
  }
  return best;
}

}  // namespace bsp
