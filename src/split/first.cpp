// `first`: the first fragment of the node's set, in input order (csg.js' choice). On a convex
// polyhedron this builds a chain as deep as the polyhedron has faces; it is the baseline every
// other heuristic must beat.
#include "split/registry.h"

namespace bsp {

namespace {

class FirstSplitter final : public Splitter {
 public:
  SplitChoice choose(const SplitContext& ctx) override { return SplitChoice::of_fragment(ctx.ids.front()); }
  std::unique_ptr<Splitter> clone() const override { return std::make_unique<FirstSplitter>(); }
};

}  // namespace

HeuristicInfo first_heuristic() {
  return {"first", "the first polygon of the set (csg.js); the baseline", {}, true,
          [](const ParamSet&, std::uint64_t) { return std::make_unique<FirstSplitter>(); }};
}

}  // namespace bsp
