// Tree builds on tiny arbitrary scenes: up to eight triangles with coordinates on a coarse grid
// (so coplanar, touching, crossing and degenerate triangles are common), a heuristic picked from
// the registry, strict or coarse leaves, recursive or incremental insertion. Every tree must pass
// the invariant validator (src/validate/tree_invariants.h).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "split/registry.h"
#include "tree/build.h"
#include "validate/tree_invariants.h"

namespace {

using namespace bsp;

Vec3 grid_point(FuzzedDataProvider& in) {
  const auto c = [&] { return in.ConsumeIntegralInRange<int>(-8, 8) / 2.0; };
  const double x = c(), y = c(), z = c();
  return {x, y, z};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const auto& all = heuristics();
  const HeuristicInfo& heuristic = all[in.ConsumeIntegralInRange<std::size_t>(0, all.size() - 1)];
  BuildOptions options;
  options.shape = in.ConsumeBool() ? Shape::Coarse : Shape::Strict;
  options.incremental = in.ConsumeBool();
  options.order = in.ConsumeBool() ? InsertOrder::Shuffled : InsertOrder::Given;
  options.order_seed = in.ConsumeIntegral<std::uint8_t>();
  const std::uint64_t seed = in.ConsumeIntegral<std::uint8_t>();
  std::vector<Polygon> input;
  for (int n = in.ConsumeIntegralInRange<int>(1, 8); n > 0 && in.remaining_bytes() > 0; --n) {
    Polygon t{{}, static_cast<std::uint32_t>(input.size())};
    for (int k = 0; k < 3; ++k) t.verts.push_back({grid_point(in), 0, 0});
    input.push_back(std::move(t));
  }
  auto splitter = make_splitter(heuristic.name, {}, seed);
  const Tree tree = build_tree(input, *splitter, options);
  const InvariantReport report = check_tree_invariants(tree, input);
  if (!report.ok()) {
    std::fprintf(stderr, "%s: %llu invariant violations\n", heuristic.name.c_str(),
                 static_cast<unsigned long long>(report.violations));
    for (const auto& p : report.first_problems) std::fprintf(stderr, "  %s\n", p.c_str());
    std::abort();
  }
  return 0;
}
