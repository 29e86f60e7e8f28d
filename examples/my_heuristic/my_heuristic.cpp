// my_heuristic: a bspbench plugin, the one to copy (docs/plugins.md). It adds one heuristic,
// `largest_first`: of the node's k largest fragments by area, the one whose plane splits the fewest
// of the node's fragments, the larger breaking ties. Large polygons first is the classic rule of
// thumb for autopartitions (Thibault and Naylor 1987); counting splits among a few candidates is
// the least-splits criterion of Fuchs, Kedem and Naylor (1980).
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include <bspbench/split/plugin.h>

namespace {

// Twice the area would do for ranking; the area itself is clearer.
double area(std::span<const bsp::Vec3> p) {
  bsp::Vec3 sum{};
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum = sum + cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * length(sum);
}

class LargestFirst final : public bsp::Splitter {
 public:
  explicit LargestFirst(std::size_t k) : k_(k) {}

  // Depends on the context only (no randomness), so any thread may build any node.
  bsp::SplitChoice choose(const bsp::SplitContext& ctx) override {
    by_area_.clear();
    for (std::uint32_t id : ctx.ids) by_area_.emplace_back(-area(ctx.frags.points(id)), id);
    const std::size_t k = std::min(k_, by_area_.size());
    std::partial_sort(by_area_.begin(), by_area_.begin() + static_cast<std::ptrdiff_t>(k), by_area_.end());
    std::uint32_t best = by_area_.front().second;
    std::uint64_t fewest = ~std::uint64_t{0};
    for (std::size_t i = 0; i < k; ++i) {
      const std::uint32_t id = by_area_[i].second;
      const bsp::Plane& plane = ctx.planes[ctx.frags.plane(id)];
      const std::uint64_t splits = ctx.frags.count_sides(ctx.ids, plane, ctx.tol.plane_eps).spanning;
      if (splits < fewest) std::tie(fewest, best) = std::pair{splits, id};
    }
    return bsp::SplitChoice::of_fragment(best);
  }

  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<LargestFirst>(k_); }

 private:
  std::size_t k_;
  std::vector<std::pair<double, std::uint32_t>> by_area_;  // scratch, reused node to node
};

bsp::PluginInfo describe() {
  bsp::HeuristicInfo largest_first{
      "largest_first",
      "of the k largest fragments, the one splitting fewest (an example plugin)",
      {{"k", bsp::ParamSpec::Kind::Integer, "candidates: the k largest fragments by area", 8, 1, 1e6, {}}},
      true,  // an autopartition: every plane is a fragment's
      [](const bsp::ParamSet& p, std::uint64_t) {
        return std::make_unique<LargestFirst>(static_cast<std::size_t>(p.integer("k")));
      }};
  return {"my_heuristic", "1.0.0", {std::move(largest_first)}};
}

}  // namespace

BSPBENCH_PLUGIN(describe)
