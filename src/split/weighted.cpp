// `weighted`: the weighted sum of splits and imbalance over sampled candidates ([Chrysanthou §7]: "select
// a few candidate polygons at each iteration and find the best of these ... the weighted sum of two
// quantities, size (number of resulting splits) and distribution (difference in the number of
// polygons in each of the resulting subsets)"), plus the coplanar and axial terms the Quake tools
// add. Cost per node: O(m) to find the distinct planes (a stamp per pooled plane), then O(k·s)
// classifications for m fragments, k candidates and s counted fragments (s = m unless `sample` is
// set; O(m²) with k = 0).
#include "split/weighted.h"

#include <cstdlib>

#include "common/rng.h"
#include "split/candidates.h"

namespace bsp {

namespace {

constexpr double kMaxWeight = 1e6;

class WeightedSplitter final : public Splitter {
 public:
  WeightedSplitter(const WeightedSettings& s, std::uint64_t seed) : s_(s), seed_(seed) {}

  std::unique_ptr<Splitter> clone() const override { return std::make_unique<WeightedSplitter>(*this); }

  SplitChoice choose(const SplitContext& ctx) override {
    Rng rng(stream_seed(seed_, ctx.node_key));
    const auto candidates = candidate_fragments(ctx, s_.candidates, rng, scratch_);
    const SideCounter count(ctx, s_.sample, rng, scratch_);
    return SplitChoice::of_fragment(argmin_candidate(count, candidates, [&](std::uint32_t id, const SideCounts& c) {
      return cost(ctx.planes[ctx.frags.plane(id)], c, count.scale());
    }));
  }

 private:
  // Counts taken over a sample are scaled to the node, so the axial bonus keeps its weight.
  double cost(const Plane& plane, const SideCounts& c, double scale) const {
    const double imbalance = std::abs(static_cast<double>(c.front) - static_cast<double>(c.back));
    return scale * (s_.split * c.spanning + s_.balance * imbalance - s_.coplanar * c.coplanar) -
           (is_axial(plane) ? s_.axial : 0.0);
  }

  WeightedSettings s_;
  std::uint64_t seed_;
  CandidateScratch scratch_;
};

ParamSpec weight_param(const char* name, const std::string& doc, double default_value) {
  return {name, ParamSpec::Kind::Real, doc, default_value, 0.0, kMaxWeight, {}};
}

std::vector<ParamSpec> weighted_params(const WeightedSettings& d, const std::string& candidates_note) {
  return {weight_param("split_weight", "cost per fragment the candidate's plane splits", d.split),
          weight_param("balance_weight", "cost per fragment of |front - back| (whole fragments on each side)",
                       d.balance),
          weight_param("coplanar_weight", "bonus per fragment lying in the candidate's plane (itself included)",
                       d.coplanar),
          weight_param("axial_weight", "bonus when the candidate's plane is axis-aligned", d.axial),
          candidates_param(static_cast<double>(d.candidates), candidates_note), sample_param(static_cast<double>(d.sample))};
}

}  // namespace

WeightedSettings WeightedSettings::from(const ParamSet& p) {
  return {p.real("split_weight"), p.real("balance_weight"), p.real("coplanar_weight"), p.real("axial_weight"),
          static_cast<std::uint64_t>(p.integer("candidates")), static_cast<std::uint64_t>(p.integer("sample"))};
}

HeuristicInfo weighted_family(std::string name, std::string summary, const WeightedSettings& defaults,
                              std::uint64_t stream, const std::string& candidates_note) {
  return {std::move(name), std::move(summary), weighted_params(defaults, candidates_note), true,
          [stream](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<WeightedSplitter>(WeightedSettings::from(p), stream_seed(seed, stream));
          }};
}

// Equal split and balance weights, sampled candidates: the neutral point the presets depart from.
HeuristicInfo weighted_heuristic() {
  return weighted_family("weighted",
                         "min split_weight*splits + balance_weight*|front-back| - coplanar/axial bonuses over "
                         "sampled candidates (Chrysanthou's BSP tutorial)",
                         WeightedSettings{}, 0x3e16);
}

}  // namespace bsp
