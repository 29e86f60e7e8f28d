#pragma once
// The weighted split/balance family [Chrysanthou §7]: score k candidate planes sampled from the node's
// fragments by a weighted sum and take the cheapest. `weighted` exposes the weights; the presets
// `quake` and `crystal` (quake.cpp, crystal.cpp) are the same scorer with the constants of the
// production tools they are named after, so each preset's constants live with their source.
#include <cstdint>
#include <string>

#include "split/candidates.h"
#include "split/registry.h"

namespace bsp {

// cost = split·spanning + balance·|front − back| − coplanar·coplanar − axial·[plane is axial],
// lower is better. front and back count whole fragments; a spanning fragment lands on both sides,
// so counting its halves would add the same to both and leave |front − back| unchanged. coplanar
// includes the candidate itself (a constant offset, as in qbsp's `facing`).
struct WeightedSettings {
  double split = 1.0;
  double balance = 1.0;
  double coplanar = 0.0;
  double axial = 0.0;
  std::uint64_t candidates = kSampledCandidates;  // 0 = every distinct plane
  std::uint64_t sample = 0;      // fragments each candidate is counted against; 0 = all

  static WeightedSettings from(const ParamSet& p);
};

// A registry entry for the weighted scorer whose parameters default to `defaults`; `stream` tells
// the presets' sampling streams apart.
// `candidates_note` ends the candidates parameter's description (what the preset's source does).
HeuristicInfo weighted_family(std::string name, std::string summary, const WeightedSettings& defaults,
                              std::uint64_t stream, const std::string& candidates_note = "");

}  // namespace bsp
