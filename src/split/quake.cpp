// `quake`: the plane score of the Quake 2 BSP compiler as ericw-tools' qbsp keeps it
// (qbsp/brushbsp.cc, SelectSplitPlane, from id's qbsp3 brushbsp.c):
//   value = 5 * facing - 5 * splits - abs(front - back); value += 5 for an axial plane;
// the highest value wins and every side of every brush is a candidate (here candidates = 0; the
// default samples, as every scorer of the suite does, so that builds scale). Here the same score, negated
// into a cost, over polygons instead of brushes: facing = fragments in the candidate's plane,
// splits = fragments it spans. qbsp counts a brush that straddles the plane on both sides, which
// leaves |front - back| the same as counting whole fragments only. Not carried over: qbsp's
// penalty for brushes that barely cross the plane (epsilonbrush), its hint-surface rules and its
// passes over visible/detail sides, which have no counterpart in a polygon soup.
#include "split/weighted.h"

namespace bsp {

namespace {

// The constants of SelectSplitPlane.
constexpr double kQuakeSplit = 5.0;
constexpr double kQuakeBalance = 1.0;
constexpr double kQuakeFacing = 5.0;
constexpr double kQuakeAxial = 5.0;

}  // namespace

HeuristicInfo quake_heuristic() {
  return weighted_family("quake",
                         "Quake 2 qbsp3 / ericw-tools score 5*coplanar - 5*splits - |front-back| + 5 if axial "
                         "(qbsp scores every candidate: candidates=0)",
                         WeightedSettings{kQuakeSplit, kQuakeBalance, kQuakeFacing, kQuakeAxial, kSampledCandidates, 0},
                         0x9a4e, kSourceScoresAll);
}

}  // namespace bsp
