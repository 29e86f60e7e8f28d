// `balanced`: the "most balanced face" of [AlphaBSP]: the candidate plane that leaves the same number of
// fragments on both sides, fewer splits breaking ties, then the earlier fragment. Counts are whole
// fragments; a spanning one lands on both sides and so does not change |front − back|. Seed 003
// scores every face (candidates = 0); sampling is there for inputs too large for O(m²) per node.
// Cost per node: O(m log m) + O(k·m) classifications.
#include <cstdlib>
#include <utility>

#include "common/rng.h"
#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

namespace {

class BalancedSplitter final : public Splitter {
 public:
  BalancedSplitter(std::uint64_t candidates, std::uint64_t seed) : candidates_(candidates), rng_(seed) {}

  SplitChoice choose(const SplitContext& ctx) override {
    const auto candidates = candidate_fragments(ctx, candidates_, rng_);
    return SplitChoice::of_fragment(argmin_candidate(ctx, candidates, [](std::uint32_t, const SideCounts& c) {
      const auto imbalance = c.front > c.back ? c.front - c.back : c.back - c.front;
      return std::pair{imbalance, c.spanning};
    }));
  }

 private:
  std::uint64_t candidates_;
  Rng rng_;
};

}  // namespace

HeuristicInfo balanced_heuristic() {
  return {"balanced",
          "most balanced plane: min |front-back|, ties by fewer splits",
          {candidates_param(0, "; the most-balanced-face method scores all")},
          true,
          [](const ParamSet& p, std::uint64_t seed) {
            return std::make_unique<BalancedSplitter>(static_cast<std::uint64_t>(p.integer("candidates")),
                                                      stream_seed(seed, 0xba1a));
          }};
}

}  // namespace bsp
