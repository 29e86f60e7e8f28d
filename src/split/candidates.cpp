#include "split/candidates.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace bsp {

bool is_axial(const Plane& p) {
  const double m = std::max({std::abs(p.n.x), std::abs(p.n.y), std::abs(p.n.z)});
  return m >= 1.0 - kAxialNormalTolerance;
}

ParamSpec candidates_param(double default_k, const std::string& doc_suffix) {
  return {"candidates", ParamSpec::Kind::Integer,
          "distinct planes sampled (seeded) from the node's fragments and scored; 0 = all" + doc_suffix,
          default_k, 0, 1e9, {}};
}

namespace {

// Positions in ctx.ids of the first fragment on each distinct plane pair, ascending.
void distinct_plane_positions(const SplitContext& ctx, PlaneMarks& marks, std::vector<std::uint32_t>& positions) {
  marks.begin(ctx.planes.size() / 2);
  positions.clear();
  const std::size_t m = ctx.ids.size();
  for (std::uint32_t i = 0; i < m; ++i) {
    // The fragments' planes are scattered through the store; the ids ahead are known.
    if (i + kPrefetchAhead < m) ctx.frags.prefetch_plane(ctx.ids[i + kPrefetchAhead]);
    if (marks.first_sight(ctx.frags.plane(ctx.ids[i]) >> 1)) positions.push_back(i);
  }
}

}  // namespace

void PlaneMarks::begin(std::size_t pairs) {
  if (stamp_.size() < pairs) stamp_.resize(pairs, pass_);
  if (++pass_ == 0) {  // the stamps wrapped: clear them once every 2^32 passes
    std::fill(stamp_.begin(), stamp_.end(), 0);
    pass_ = 1;
  }
}

std::span<const std::uint32_t> candidate_fragments(const SplitContext& ctx, std::size_t k, Rng& rng,
                                                   CandidateScratch& scratch) {
  std::vector<std::uint32_t>& positions = scratch.positions;
  distinct_plane_positions(ctx, scratch.marks, positions);
  if (k > 0 && k < positions.size()) {
    // Partial Fisher-Yates: the first k entries become a uniform sample without replacement.
    for (std::size_t i = 0; i < k; ++i) std::swap(positions[i], positions[i + rng.below(positions.size() - i)]);
    positions.resize(k);
    std::sort(positions.begin(), positions.end());
  }
  scratch.candidates.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) scratch.candidates[i] = ctx.ids[positions[i]];
  return scratch.candidates;
}

ParamSpec sample_param(double default_s) {
  return {"sample", ParamSpec::Kind::Integer,
          "fragments of the node (drawn once per node, seeded) each candidate is counted against, the counts "
          "scaled to the node; 0 = all",
          default_s, 0, 1e9, {}};
}

SideCounter::SideCounter(const SplitContext& ctx, std::size_t s, Rng& rng, CandidateScratch& scratch)
    : ctx_(ctx), scratch_(scratch) {
  const std::size_t m = ctx.ids.size();
  if (s == 0 || s >= m) return;
  std::vector<std::uint32_t> positions(m);
  for (std::uint32_t i = 0; i < m; ++i) positions[i] = i;
  for (std::size_t i = 0; i < s; ++i) std::swap(positions[i], positions[i + rng.below(m - i)]);
  positions.resize(s);
  std::sort(positions.begin(), positions.end());
  sampled_.resize(s);
  for (std::size_t i = 0; i < s; ++i) sampled_[i] = ctx.ids[positions[i]];
  scale_ = static_cast<double>(m) / static_cast<double>(s);
}

std::span<const SideCounts> SideCounter::operator()(std::span<const std::uint32_t> candidates) const {
  const std::span<const std::uint32_t> counted = sampled_.empty() ? ctx_.ids : std::span<const std::uint32_t>(sampled_);
  std::vector<SideCounts>& counts = scratch_.counts;
  counts.assign(candidates.size(), SideCounts{});
  if (ctx_.exact) {
    std::vector<std::uint32_t>& planes = scratch_.pooled;
    planes.clear();
    for (auto id : candidates) planes.push_back(ctx_.exact->plane(id));
    ctx_.exact->count_sides(counted, planes, counts);
    return counts;
  }
  std::vector<Plane>& planes = scratch_.planes;
  planes.clear();
  for (auto id : candidates) planes.push_back(ctx_.planes[ctx_.frags.plane(id)]);
  ctx_.frags.count_sides(counted, planes, ctx_.tol.plane_eps, counts);
  return counts;
}

}  // namespace bsp
