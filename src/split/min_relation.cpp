// `min-relation`: CHOOSE-DIVIDING-POLYGON of [DividingPolygon]. Among the candidates, the fewest spanning
// fragments subject to relation = min(front, back) / max(front, back) > MinRelation, ties going to
// the better relation, then to the earlier fragment; when no candidate qualifies, MinRelation is
// divided by MINRELATIONSCALE and the search repeats. Every fragment of a node is "unused" in the
// seed's sense: fragments lying in an ancestor's plane are stored at that ancestor.
//
// The seed begins with `if IS-CONVEX-SET return NOPOLYGON`; the coarse shape's build loop makes that
// test before asking the splitter. In the strict shape a convex set does reach this heuristic, and
// there every candidate has an empty side (relation 0), which no threshold exceeds, so the seed's
// loop would not end: then every candidate qualifies and the fewest splits decide.
//
// Counting once and lowering the threshold over the stored counts picks what the seed's recount per
// round picks. Cost per node: O(m) + O(k·s) classifications (s = sample, or m).
#include <algorithm>
#include <vector>

#include "common/rng.h"
#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

namespace {

// Relation of a candidate with nothing on either side (every other fragment coplanar or spanning):
// both sets are equally large, the best possible relation.
constexpr double kRelationOfEmptySides = 1.0;

struct MinRelationSettings {
  double min_relation;  // MINIMUMRELATION [DividingPolygon]
  double scale;         // MINRELATIONSCALE [DividingPolygon]
  std::uint64_t candidates;
  std::uint64_t sample;

  static MinRelationSettings from(const ParamSet& p) {
    return {p.real("min_relation"), p.real("min_relation_scale"), static_cast<std::uint64_t>(p.integer("candidates")),
            static_cast<std::uint64_t>(p.integer("sample"))};
  }
};

struct Scored {
  std::uint32_t id;
  std::uint32_t spanning;
  double relation;
};

double relation(const SideCounts& c) {
  const auto hi = std::max(c.front, c.back);
  return hi == 0 ? kRelationOfEmptySides : static_cast<double>(std::min(c.front, c.back)) / hi;
}

class MinRelationSplitter final : public Splitter {
 public:
  MinRelationSplitter(const MinRelationSettings& s, std::uint64_t seed) : s_(s), seed_(seed) {}

  std::unique_ptr<Splitter> clone() const override { return std::make_unique<MinRelationSplitter>(*this); }

  SplitChoice choose(const SplitContext& ctx) override {
    std::vector<Scored> scored;
    Rng rng(stream_seed(seed_, ctx.node_key));
    const auto candidates = candidate_fragments(ctx, s_.candidates, rng, scratch_);
    const SideCounter count(ctx, s_.sample, rng, scratch_);
    const std::span<const SideCounts> counts = count(candidates);
    for (std::size_t i = 0; i < candidates.size(); ++i)
      scored.push_back({candidates[i], counts[i].spanning, relation(counts[i])});
    return SplitChoice::of_fragment(best_qualifying(scored, threshold(scored)));
  }

 private:
  // The first MinRelation / scale^i that some candidate's relation exceeds ([DividingPolygon]),
  // or -1 when every relation is 0.
  double threshold(const std::vector<Scored>& scored) const {
    double best = 0;
    for (const auto& s : scored) best = std::max(best, s.relation);
    if (best == 0) return -1;
    double t = s_.min_relation;
    while (!(best > t)) t /= s_.scale;
    return t;
  }

  // CHOOSE-DIVIDING-POLYGON's final pick [DividingPolygon]: fewest spanning among those above the
  // threshold, ties by relation.
  static std::uint32_t best_qualifying(const std::vector<Scored>& scored, double t) {
    const Scored* best = nullptr;
    for (const auto& s : scored) {
      if (!(s.relation > t)) continue;
      if (!best || s.spanning < best->spanning || (s.spanning == best->spanning && s.relation > best->relation))
        best = &s;
    }
    return best->id;
  }

  MinRelationSettings s_;
  std::uint64_t seed_;
  CandidateScratch scratch_;
};

}  // namespace

HeuristicInfo min_relation_heuristic() {
  return {"min-relation",
          "fewest splits subject to min(front,back)/max(front,back) > min_relation, relaxed by "
          "min_relation_scale until one qualifies (dividing-polygon method)",
          {{"min_relation", ParamSpec::Kind::Real,
            "MINIMUMRELATION: the balance min(front,back)/max(front,back) a candidate must exceed first",
            0.8, 0.0, 1.0, {}},
           {"min_relation_scale", ParamSpec::Kind::Real,
            "MINRELATIONSCALE: divides the threshold after a round with no qualifying candidate (>= 2 "
            "keeps the rounds O(log m))",
            2.0, 2.0, 1e6, {}},
           candidates_param(static_cast<double>(kSampledCandidates), "; the dividing-polygon method scores all (candidates = 0)"),
           sample_param(0)},
          true,
          [](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<MinRelationSplitter>(MinRelationSettings::from(p), stream_seed(seed, 0x4e1a));
          }};
}

}  // namespace bsp
