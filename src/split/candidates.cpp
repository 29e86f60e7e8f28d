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
std::vector<std::uint32_t> distinct_plane_positions(const SplitContext& ctx, PlaneMarks& marks) {
  marks.begin(ctx.planes.size() / 2);
  std::vector<std::uint32_t> positions;
  for (std::uint32_t i = 0; i < ctx.ids.size(); ++i)
    if (marks.first_sight(ctx.frags.plane(ctx.ids[i]) >> 1)) positions.push_back(i);
  return positions;
}

}  // namespace

void PlaneMarks::begin(std::size_t pairs) {
  if (stamp_.size() < pairs) stamp_.resize(pairs, pass_);
  if (++pass_ == 0) {  // the stamps wrapped: clear them once every 2^32 passes
    std::fill(stamp_.begin(), stamp_.end(), 0);
    pass_ = 1;
  }
}

std::vector<std::uint32_t> candidate_fragments(const SplitContext& ctx, std::size_t k, Rng& rng, PlaneMarks& marks) {
  std::vector<std::uint32_t> positions = distinct_plane_positions(ctx, marks);
  if (k > 0 && k < positions.size()) {
    // Partial Fisher-Yates: the first k entries become a uniform sample without replacement.
    for (std::size_t i = 0; i < k; ++i) std::swap(positions[i], positions[i + rng.below(positions.size() - i)]);
    positions.resize(k);
    std::sort(positions.begin(), positions.end());
  }
  std::vector<std::uint32_t> ids(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) ids[i] = ctx.ids[positions[i]];
  return ids;
}

ParamSpec sample_param(double default_s) {
  return {"sample", ParamSpec::Kind::Integer,
          "fragments of the node (drawn once per node, seeded) each candidate is counted against, the counts "
          "scaled to the node; 0 = all",
          default_s, 0, 1e9, {}};
}

SideCounter::SideCounter(const SplitContext& ctx, std::size_t s, Rng& rng) : ctx_(ctx) {
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

std::vector<SideCounts> SideCounter::operator()(std::span<const std::uint32_t> candidates) const {
  const std::span<const std::uint32_t> counted = sampled_.empty() ? ctx_.ids : std::span<const std::uint32_t>(sampled_);
  if (ctx_.exact) {
    std::vector<std::uint32_t> planes;
    planes.reserve(candidates.size());
    for (auto id : candidates) planes.push_back(ctx_.exact->plane(id));
    std::vector<SideCounts> counts(candidates.size());
    ctx_.exact->count_sides(counted, planes, counts);
    return counts;
  }
  std::vector<Plane> planes;
  planes.reserve(candidates.size());
  for (auto id : candidates) planes.push_back(ctx_.planes[ctx_.frags.plane(id)]);
  std::vector<SideCounts> counts(candidates.size());
  ctx_.frags.count_sides(counted, planes, ctx_.tol.plane_eps, counts);
  return counts;
}

}  // namespace bsp
