#include "solid_pairs.h"

#include "catalog.h"
#include "common/errors.h"

namespace bsp {

namespace {

// Two copies of one generator, the second placed by `second_placement`. `sized`: n goes to both
// operands, within the range their generator accepts; false for a generator that declares `n` but
// ignores it (the sponge: its level sets the count).
SolidPairInfo pair(std::string name, std::string generator, ParamAssignments second_placement,
                   ParamAssignments first_placement = {}, bool sized = true) {
  SolidPairInfo p{std::move(name), generator, generator, std::move(first_placement), std::move(second_placement), sized};
  for (const auto& spec : find_generator(generator).params)
    if (sized && spec.name == "n") {
      p.min_n = spec.min;
      p.max_n = spec.max;
    }
  return p;
}

// What each pair exercises:
//  spheres       convex operands whose autopartitions are chains; centres half a radius apart
//  tori          operands with holes, one moved along its ring's radius, rotated independently
//  cylinders     flat caps and long side faces, rotated independently across each other
//  polytopes     two random convex polytopes (independent planes), half a radius apart
//  hollow-boxes  non-convex, cavities overlapping, moved along the diagonal
//  sponges       two level-2 Menger sponges (1,056 quads each) off each other's voxel grid: tunnels,
//                coplanar faces
std::vector<SolidPairInfo> make_pairs() {
  return {
      pair("spheres", "sphere", {{"x", "0.5"}}),
      pair("tori", "torus", {{"x", "0.6"}, {"y", "0.2"}}),
      pair("cylinders", "cylinder", {{"x", "0.3"}, {"y", "0.2"}}),
      pair("polytopes", "convex-polytope", {{"x", "0.5"}}),
      pair("hollow-boxes", "hollow-box", {{"x", "0.4"}, {"y", "0.3"}, {"z", "0.2"}}),
      pair("sponges", "menger-sponge", {{"x", "0.35"}, {"y", "0.25"}, {"z", "0.15"}, {"level", "2"}}, {{"level", "2"}},
           false),
  };
}

SolidOperand operand(const std::string& scene, const ParamAssignments& placement, bool sized, std::uint64_t n,
                     std::uint64_t seed) {
  SolidOperand o{scene, placement};
  if (sized) o.params.emplace_back("n", std::to_string(n));
  o.params.emplace_back("seed", std::to_string(seed));
  return o;
}

}  // namespace

std::array<SolidOperand, 2> SolidPairInfo::operands(std::uint64_t n, std::uint64_t seed) const {
  return {operand(first, first_placement, sized, n, seed),
          operand(second, second_placement, sized, n, seed + kSecondSeedOffset)};
}

const std::vector<SolidPairInfo>& solid_pairs() {
  static const std::vector<SolidPairInfo> all = make_pairs();
  return all;
}

const SolidPairInfo& find_solid_pair(std::string_view name) {
  std::string known;
  for (const auto& p : solid_pairs()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw UsageError("unknown solid pair '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace bsp
