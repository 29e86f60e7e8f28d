#pragma once
// Naylor's per-frame merge [Naylor1990; Chrysanthou §8]: the static polygons' tree is built once
// and never edited; each moving object's tree is built once at its first pose. Every frame the
// previous frame's object parts are dropped (the static tree comes back as built) and each object's
// tree, moved to its pose, is merged into the static tree (dynamic/object_tree.h), one object after
// another, so later objects also merge into earlier ones.
#include <memory>
#include <optional>
#include <vector>

#include "dynamic/kept_tree.h"
#include "dynamic/object_tree.h"

namespace bsp {

class MergeUpdater final : public KeptTreeUpdater {
 public:
  // `splitter` builds the static tree, `object_splitter` the objects' trees.
  MergeUpdater(std::unique_ptr<Splitter> splitter, std::unique_ptr<Splitter> object_splitter)
      : splitter_(std::move(splitter)), object_splitter_(std::move(object_splitter)) {}
  UpdateWork start(std::span<const Polygon> static_polys, std::span<const Polygon> moving, std::size_t objects) override;
  UpdateWork update(std::span<const Polygon> moving) override;

 private:
  void place_all(std::span<const Polygon> moving, UpdateWork& work);

  std::unique_ptr<Splitter> splitter_, object_splitter_;
  std::vector<ObjectTree> objects_;
  std::vector<std::uint32_t> owners_;
};

}  // namespace bsp
