// `zennode`: the partition metric of ZenNode's "classic" algorithm [ZenNode], the node builder whose
// nodes Freedoom ships. For a candidate with L fragments behind it, R in front and S split:
//
//   metric = L·R                                   when S = 0,
//   metric = L·R·X2 / (X1·S) − (X3·S + X4)·S      otherwise (the division only when X2 < X1·S),
//
// in integer arithmetic as the source computes it, and the largest metric wins. Unlike a
// fewest-splits rule it trades a split for balance: with the source's constants a split costs
// halving L·R and 26 more, so a node of 100 fragments prefers one split that halves the rest
// (49·50/2 − 26 = 1,199) to no split that peels one fragment off (99); balanced children then need
// fewer splits below. The arithmetic is 128-bit, so no count or constant in range overflows.
// Ties go to the smaller |L − R|, then to the earlier fragment. A candidate with nothing behind it
// and nothing split (L·R + S = 0, the source's "boundary line") is not taken while any other
// candidate divides the node. Coplanar fragments count in front, where the candidate's own
// fragment lies. Cost per node: O(m) + O(k·s) classifications (candidates.h).
#include <cstdint>
#include <limits>
#include <tuple>

#include "common/rng.h"
#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

namespace {

struct ZenNodeSettings {
  __int128 x1, x2, x3, x4;  // the source's ZEN_X1..ZEN_X4
  std::uint64_t candidates;
  std::uint64_t sample;

  static ZenNodeSettings from(const ParamSet& p) {
    return {p.integer("x1"), p.integer("x2"), p.integer("x3"), p.integer("x4"),
            static_cast<std::uint64_t>(p.integer("candidates")), static_cast<std::uint64_t>(p.integer("sample"))};
  }

  __int128 metric(const SideCounts& c) const {
    const __int128 left = c.back, right = c.front + c.coplanar, split = c.spanning;
    __int128 m = left * right;
    if (split == 0) return m;
    if (x2 < x1 * split) m = x2 * m / (x1 * split);
    return m - (x3 * split + x4) * split;
  }
};

class ZenNodeSplitter final : public Splitter {
 public:
  ZenNodeSplitter(const ZenNodeSettings& s, std::uint64_t seed) : s_(s), seed_(seed) {}

  std::unique_ptr<Splitter> clone() const override { return std::make_unique<ZenNodeSplitter>(*this); }

  SplitChoice choose(const SplitContext& ctx) override {
    Rng rng(stream_seed(seed_, ctx.node_key));
    const auto candidates = candidate_fragments(ctx, s_.candidates, rng, scratch_);
    const SideCounter count(ctx, s_.sample, rng, scratch_);
    return SplitChoice::of_fragment(argmin_candidate(count, candidates, [this](std::uint32_t, const SideCounts& c) {
      const bool boundary = c.back == 0 && c.spanning == 0;
      const std::int64_t imbalance = static_cast<std::int64_t>(c.front) + c.coplanar - c.back;
      // argmin: a boundary line last, then the largest metric, then the best balance.
      return std::tuple{boundary, -s_.metric(c), imbalance < 0 ? -imbalance : imbalance};
    }));
  }

 private:
  ZenNodeSettings s_;
  std::uint64_t seed_;
  CandidateScratch scratch_;
};

ParamSpec constant(const char* name, double value, const char* doc) {
  return {name, ParamSpec::Kind::Integer, doc, value, 0.0, 1e6, {}};
}

}  // namespace

HeuristicInfo zennode_heuristic() {
  return {"zennode",
          "ZenNode's classic metric: L*R, divided by X1*S/X2 and reduced by (X3*S+X4)*S when S fragments are split",
          {constant("x1", 20, "ZEN_X1: with X2, how much one split divides L*R (by X1*S/X2)"),
           constant("x2", 10, "ZEN_X2: see x1"),
           constant("x3", 1, "ZEN_X3: the quadratic penalty per split (X3*S*S)"),
           constant("x4", 25, "ZEN_X4: the linear penalty per split (X4*S)"),
           candidates_param(0, kSourceScoresAll), sample_param(0)},
          true,
          [](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<ZenNodeSplitter>(ZenNodeSettings::from(p), stream_seed(seed, 0x2e4e));
          }};
}

}  // namespace bsp
