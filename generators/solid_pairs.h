#pragma once
// Pairs of closed solids placed to overlap: the operands of the set operations that the merge
// suites measure (sweep) and that `bspbench merge` reproduces. A pair names two solid generators
// (solids.cpp) with their placements; the size n, when the pair has one, goes to both operands,
// and the pair's seed s gives the first operand seed s and the second seed s + kSecondSeedOffset,
// so the two are rotated (and, for random polytopes, drawn) independently.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/params.h"

namespace bsp {

inline constexpr std::uint64_t kSecondSeedOffset = 1000;

struct SolidOperand {
  std::string scene;         // a closed-solid generator
  ParamAssignments params;   // resolved for one size and seed: give them to make_scene
};

struct SolidPairInfo {
  std::string name;
  std::string first, second;          // generators
  ParamAssignments first_placement, second_placement;  // fixed parameters (position, level, ...)
  bool sized = true;  // false: n is not used and the pair has one size
  double min_n = 0, max_n = 0;  // the n both operands accept, when sized
  // The operands for size n (ignored unless sized) and seed s.
  std::array<SolidOperand, 2> operands(std::uint64_t n, std::uint64_t seed) const;
};

const std::vector<SolidPairInfo>& solid_pairs();
// Throws UsageError naming the known pairs.
const SolidPairInfo& find_solid_pair(std::string_view name);

}  // namespace bsp
