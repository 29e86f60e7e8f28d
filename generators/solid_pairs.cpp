#include "solid_pairs.h"

#include "catalog.h"
#include "common/errors.h"

namespace bsp {

namespace {

SolidPairInfo pair(std::string name, std::string purpose, std::string generator, ParamAssignments second_placement) {
  return {std::move(name), std::move(purpose), generator, generator, {}, std::move(second_placement)};
}

// The n range both operands accept (their generators' `n`), or unsized when they have none.
SolidPairInfo with_sizes(SolidPairInfo p) {
  for (const auto& spec : find_generator(p.first).params)
    if (spec.name == "n") {
      p.min_n = spec.min;
      p.max_n = spec.max;
      return p;
    }
  p.sized = false;
  return p;
}

std::vector<SolidPairInfo> make_pairs() {
  std::vector<SolidPairInfo> pairs = {
      pair("spheres", "two spheres, centres half a radius apart: convex operands whose autopartitions are chains",
           "sphere", {{"x", "0.5"}}),
      pair("tori", "two tori, one moved along its ring's radius, rotated independently: operands with holes",
           "torus", {{"x", "0.6"}, {"y", "0.2"}}),
      pair("cylinders", "two cylinders, rotated independently across each other: flat caps and long side faces",
           "cylinder", {{"x", "0.3"}, {"y", "0.2"}}),
      pair("polytopes", "two random convex polytopes (independent planes), half a radius apart",
           "convex-polytope", {{"x", "0.5"}}),
      pair("hollow-boxes", "two cubes with cavities, moved along the diagonal: non-convex, cavities overlap",
           "hollow-box", {{"x", "0.4"}, {"y", "0.3"}, {"z", "0.2"}}),
      pair("sponges", "two level-2 Menger sponges (1,056 quads each) moved off the voxel grid: tunnels, coplanar faces",
           "menger-sponge", {{"x", "0.35"}, {"y", "0.25"}, {"z", "0.15"}, {"level", "2"}}),
  };
  pairs.back().first_placement = {{"level", "2"}};
  for (auto& p : pairs) p = with_sizes(std::move(p));
  // The sponge's `n` is declared but unused: its level sets the count.
  pairs.back().sized = false;
  return pairs;
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
