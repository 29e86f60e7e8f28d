// `random`: a uniformly random fragment of the node's set, seeded: the random autopartition of
// Paterson and Yao ("Efficient binary space partitions for hidden-surface removal and solid
// modeling", 1990), whose expected size is O(n log n) for disjoint segments in the plane and O(n^2)
// for polygons in space.
#include "common/rng.h"
#include "split/registry.h"

namespace bsp {

namespace {

class RandomSplitter final : public Splitter {
 public:
  explicit RandomSplitter(std::uint64_t seed) : seed_(seed) {}
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<RandomSplitter>(*this); }
  SplitChoice choose(const SplitContext& ctx) override {
    Rng rng(stream_seed(seed_, ctx.node_key));
    return SplitChoice::of_fragment(ctx.ids[rng.below(ctx.ids.size())]);
  }

 private:
  std::uint64_t seed_;
};

}  // namespace

HeuristicInfo random_heuristic() {
  return {"random", "a seeded uniformly random polygon of the set (Paterson-Yao random autopartition)", {}, true,
          [](const ParamSet&, std::uint64_t seed) { return std::make_unique<RandomSplitter>(stream_seed(seed, 0x5eed)); }};
}

}  // namespace bsp
