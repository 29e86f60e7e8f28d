// `balanced`: the "most balanced face" of [AlphaBSP]: the candidate plane that leaves the same number of
// fragments on both sides, fewer splits breaking ties, then the earlier fragment. Counts are whole
// fragments; a spanning one lands on both sides and so does not change |front − back|. The
// method scores every face (candidates = 0); the default samples, as every scorer of the suite
// does, so that builds scale.
// Cost per node: O(m) + O(k·s) classifications (s = sample, or m; candidates.h).
#include <cstdlib>
#include <utility>

#include "common/rng.h"
#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

namespace {

class BalancedSplitter final : public Splitter {
 public:
  BalancedSplitter(std::uint64_t candidates, std::uint64_t sample, std::uint64_t seed)
      : candidates_(candidates), sample_(sample), seed_(seed) {}

  std::unique_ptr<Splitter> clone() const override { return std::make_unique<BalancedSplitter>(*this); }

  SplitChoice choose(const SplitContext& ctx) override {
    Rng rng(stream_seed(seed_, ctx.node_key));
    const auto candidates = candidate_fragments(ctx, candidates_, rng, scratch_);
    const SideCounter count(ctx, sample_, rng, scratch_);
    return SplitChoice::of_fragment(argmin_candidate(count, candidates, [](std::uint32_t, const SideCounts& c) {
      const auto imbalance = c.front > c.back ? c.front - c.back : c.back - c.front;
      return std::pair{imbalance, c.spanning};
    }));
  }

 private:
  std::uint64_t candidates_, sample_, seed_;
  CandidateScratch scratch_;
};

}  // namespace

HeuristicInfo balanced_heuristic() {
  return {"balanced",
          "most balanced plane: min |front-back|, ties by fewer splits",
          {candidates_param(static_cast<double>(kSampledCandidates), "; the most-balanced-face method scores all (candidates = 0)"),
           sample_param(0)},
          true,
          [](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<BalancedSplitter>(static_cast<std::uint64_t>(p.integer("candidates")),
                                                      static_cast<std::uint64_t>(p.integer("sample")),
                                                      stream_seed(seed, 0xba1a));
          }};
}

}  // namespace bsp
