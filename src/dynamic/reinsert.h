#pragma once
// Chrysanthou and Slater's remove-and-reinsert [ChrysanthouSlater1992]: the first frame is one build
// of the whole scene; afterwards the moving objects' fragments, and the nodes only they defined, are
// removed, and their polygons at their new places inserted from the root: filtered down the tree
// and built by the run's heuristic wherever they reach an empty cell. A removed node with two
// non-empty subtrees is repaired by reinserting the smaller subtree's fragments into the larger
// (UpdateWork::repairs), which is how the static part of the tree degrades over frames.
//
// Order: `reinsert` removes every object before inserting any, so after the first update no
// object's node lies above another's fragments and repairs stop; `reinsert-each` removes and
// reinserts one object at a time, as the method is usually stated, so an object inserted below
// another's nodes makes a repair when that other object is removed, every frame.
#include <memory>
#include <optional>

#include "dynamic/kept_tree.h"

namespace bsp {

class ReinsertUpdater final : public KeptTreeUpdater {
 public:
  ReinsertUpdater(std::unique_ptr<Splitter> splitter, bool one_at_a_time)
      : splitter_(std::move(splitter)), one_at_a_time_(one_at_a_time) {}
  UpdateWork start(std::span<const Polygon> static_polys, std::span<const Polygon> moving, std::size_t objects) override;
  UpdateWork update(std::span<const Polygon> moving) override;

 private:
  std::unique_ptr<Splitter> splitter_;
  bool one_at_a_time_;
  std::size_t objects_ = 0;
};

}  // namespace bsp
