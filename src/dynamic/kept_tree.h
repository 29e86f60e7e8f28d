#pragma once
// The strategies that keep one mutable tree across frames (reinsert, merge, torres): the tree, and
// its frozen snapshot for tree(), taken on first request after each update (outside the timed
// update) and dropped by the next.
#include <memory>
#include <optional>
#include <span>

#include "dynamic/dynamic_tree.h"
#include "dynamic/update_strategy.h"
#include "split/splitter.h"

namespace bsp {

class KeptTreeUpdater : public Updater {
 public:
  const Tree& tree() const final {
    if (!snapshot_) snapshot_ = tree_->snapshot();
    return *snapshot_;
  }

 protected:
  // Call after every change of tree_.
  void changed() { snapshot_.reset(); }
  // The static polygons' tree alone, built once by `splitter` (merge and torres start so).
  void build_static(std::span<const Polygon> static_polys, std::span<const Polygon> moving, std::size_t objects,
                    const Splitter& splitter, UpdateWork& work) {
    tree_.emplace(static_polys, objects, objects ? moving.size() / objects : 0, bounds_of(static_polys, moving));
    const std::unique_ptr<Splitter> s = splitter.clone();
    tree_->build_all({}, *s, work);
    changed();
  }
  std::optional<DynamicTree> tree_;

 private:
  mutable std::optional<Tree> snapshot_;
};

}  // namespace bsp
