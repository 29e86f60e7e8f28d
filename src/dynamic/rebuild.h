#pragma once
// The baseline strategy: every frame is built from scratch with the run's heuristic.
#include <memory>
#include <vector>

#include "dynamic/update_strategy.h"
#include "split/splitter.h"
#include "tree/build.h"

namespace bsp {

class RebuildUpdater final : public Updater {
 public:
  RebuildUpdater(std::unique_ptr<Splitter> splitter, const BuildOptions& build);
  UpdateWork start(std::span<const Polygon> static_polys, std::span<const Polygon> moving, std::size_t objects) override;
  UpdateWork update(std::span<const Polygon> moving) override;
  const Tree& tree() const override { return tree_; }

 private:
  std::unique_ptr<Splitter> splitter_;
  BuildOptions build_;
  std::vector<Polygon> input_;  // the static polygons, then this frame's moving ones
  std::size_t static_count_ = 0;
  Tree tree_;
};

}  // namespace bsp
