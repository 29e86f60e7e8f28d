#pragma once
// Keeping a scene's tree valid while some of its objects move: the interface every update strategy
// a dynamic-scene run compares implements [Chrysanthou §8], apart from the factory that names them
// all (dynamic/updater.h), which includes every strategy. A frame's input is the static polygons
// (fixed for the whole run) and the moving polygons, object by object in blocks of equal size,
// always in the same layout. After every update, tree() is the tree of the static polygons and the
// moving ones at their new places, valid for any eye.
#include <cstddef>
#include <span>

#include "dynamic/update_work.h"
#include "geometry/polygon.h"
#include "tree/tree.h"

namespace bsp {

class Updater {
 public:
  virtual ~Updater() = default;
  // The first frame. `moving` holds `objects` blocks of moving.size() / objects polygons.
  virtual UpdateWork start(std::span<const Polygon> static_polys, std::span<const Polygon> moving,
                           std::size_t objects) = 0;
  // The next frame: the moving polygons at their new places, in start()'s layout.
  virtual UpdateWork update(std::span<const Polygon> moving) = 0;
  virtual const Tree& tree() const = 0;
};

}  // namespace bsp
