// A well-formed plugin for the tests: `test_first_plugin`, the first fragment of the node (as the
// built-in `first`), and `test_throws`, which throws once a node is deep enough, and
// `test_outside`, which picks a fragment not in the node, and `test_free_autopartition`, a free
// plane from a heuristic declared an autopartition, for the fault paths
// (experiments/plugin_loader.cpp).
#include <stdexcept>

#include "split/plugin.h"

namespace {

class First final : public bsp::Splitter {
 public:
  bsp::SplitChoice choose(const bsp::SplitContext& ctx) override { return bsp::SplitChoice::of_fragment(ctx.ids.front()); }
  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<First>(); }
};

class Throws final : public bsp::Splitter {
 public:
  explicit Throws(std::uint32_t depth) : depth_(depth) {}
  bsp::SplitChoice choose(const bsp::SplitContext& ctx) override {
    if (ctx.depth >= depth_) throw std::runtime_error("test_throws: deep enough at depth " + std::to_string(ctx.depth));
    return bsp::SplitChoice::of_fragment(ctx.ids.front());
  }
  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<Throws>(depth_); }

 private:
  std::uint32_t depth_;
};

// Declared an autopartition, yet answers a free plane.
class FreePlane final : public bsp::Splitter {
 public:
  bsp::SplitChoice choose(const bsp::SplitContext&) override { return bsp::SplitChoice::free_plane({{0, 0, 1}, 0}); }
  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<FreePlane>(); }
};

class Outside final : public bsp::Splitter {
 public:
  bsp::SplitChoice choose(const bsp::SplitContext&) override { return bsp::SplitChoice::of_fragment(0xfffffffe); }
  std::unique_ptr<bsp::Splitter> clone() const override { return std::make_unique<Outside>(); }
};

bsp::PluginInfo describe() {
  bsp::PluginInfo info{"test_plugin", "0.0.1", {}};
  info.heuristics.push_back({"test_first_plugin", "the first fragment (a test plugin)", {}, true,
                             [](const bsp::ParamSet&, std::uint64_t) { return std::make_unique<First>(); }});
  info.heuristics.push_back(
      {"test_throws", "throws at a depth (a test plugin)",
       {{"depth", bsp::ParamSpec::Kind::Integer, "the depth at which choose() throws", 1, 1, 1e6, {}}}, true,
       [](const bsp::ParamSet& p, std::uint64_t) { return std::make_unique<Throws>(static_cast<std::uint32_t>(p.integer("depth"))); }});
  info.heuristics.push_back({"test_outside", "a fragment not in the node (a test plugin)", {}, true,
                             [](const bsp::ParamSet&, std::uint64_t) { return std::make_unique<Outside>(); }});
  info.heuristics.push_back({"test_free_autopartition", "a free plane, declared an autopartition (a test plugin)", {},
                             true, [](const bsp::ParamSet&, std::uint64_t) { return std::make_unique<FreePlane>(); }});
  return info;
}

}  // namespace

BSPBENCH_PLUGIN(describe)
