#pragma once
// Torres' object trees [Torres1990; Chrysanthou §8]: each moving object has its own tree, built
// once (with halving planes by default) and moved rigidly; objects sit in the static tree's cells,
// and objects that meet in one cell are kept apart by separating planes between their bounding
// spheres. An object that stays inside its cell (in front of every plane its placement passed,
// separating planes included) moves without rebuilding anything: its nodes' planes and fragments
// are moved in place (UpdateWork::moved_nodes). One that leaves its cell, or that shares nodes with
// another object (its sphere crossed a plane, or no separating plane existed), is removed and
// placed again from the root: the smallest repair, touching only that object's nodes.
#include <memory>
#include <optional>
#include <vector>

#include "dynamic/kept_tree.h"
#include "dynamic/object_tree.h"

namespace bsp {

class TorresUpdater final : public KeptTreeUpdater {
 public:
  // `splitter` builds the static tree, `object_splitter` the objects' trees.
  TorresUpdater(std::unique_ptr<Splitter> splitter, std::unique_ptr<Splitter> object_splitter)
      : splitter_(std::move(splitter)), object_splitter_(std::move(object_splitter)) {}
  UpdateWork start(std::span<const Polygon> static_polys, std::span<const Polygon> moving, std::size_t objects) override;
  UpdateWork update(std::span<const Polygon> moving) override;

 private:
  bool stays(std::uint32_t k, const BoundingSphere& s) const;

  std::unique_ptr<Splitter> splitter_, object_splitter_;
  std::vector<ObjectTree> objects_;
  std::vector<Placement> placements_;
};

}  // namespace bsp
