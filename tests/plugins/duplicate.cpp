// A plugin registering a heuristic under a built-in's name, `naylor`: the loader must refuse it.
#include "split/plugin.h"

namespace {

class First final : public bsp::Splitter {
 public:
  bsp::SplitChoice choose(const bsp::SplitContext& ctx) override { return bsp::SplitChoice::of_fragment(ctx.ids.front()); }
  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<First>(); }
};

bsp::PluginInfo describe() {
  return {"duplicate", "0.0.1",
          {{"naylor", "a second naylor", {}, true,
            [](const bsp::ParamSet&, std::uint64_t) { return std::make_unique<First>(); }}}};
}

}  // namespace

BSPBENCH_PLUGIN(describe)
