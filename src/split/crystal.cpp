// `crystal`: the defaults of Crystal Space's BSP builder (libs/csengine, csBspTree::SelectSplitter,
// Jorrit Tyberghein 1998-2000): balance_factor = 1 and split_factor = 4 for the BALANCE_AND_SPLITS
// modes, and in the ALMOST_ mode at most 20 randomly drawn candidates. Crystal Space's penalty is
// (balance_factor·|front + splits − back| + split_factor·splits) / n. Differences kept on purpose so
// the preset shares the family's scorer: the balance term here is the symmetric |front − back|
// (Crystal Space puts spanning polygons on the front side only), each candidate is classified
// against all of the node's fragments (Crystal Space against 20 more random draws: `sample=20`), and the 20
// candidates are drawn without replacement from the distinct planes (Crystal Space: rand() % n,
// with replacement). Dividing by n does not change the argmin and is dropped.
#include "split/weighted.h"

namespace bsp {

namespace {

constexpr double kCrystalSplit = 4.0;
constexpr double kCrystalBalance = 1.0;
constexpr std::uint64_t kCrystalCandidates = 20;

}  // namespace

HeuristicInfo crystal_heuristic() {
  return weighted_family("crystal", "Crystal Space: min |front-back| + 4*splits over 20 sampled candidates",
                         WeightedSettings{kCrystalSplit, kCrystalBalance, 0.0, 0.0, kCrystalCandidates, 0}, 0xc5a1);
}

}  // namespace bsp
