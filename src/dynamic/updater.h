#pragma once
// Keeping a scene's tree valid while some of its objects move: one interface for the update
// strategies a dynamic-scene run compares [Chrysanthou §8]. A frame's input is the static polygons
// (fixed for the whole run) and the moving polygons, object by object in blocks of equal size,
// always in the same layout. After every update, tree() is the tree of the static polygons and the
// moving ones at their new places, valid for any eye.
//
// rebuild: a full build per frame, the baseline every other strategy is measured against.
// reinsert, reinsert-each: remove the moving objects and insert them again [ChrysanthouSlater1992]
//   (reinsert.h: all removed first, or one object at a time).
// merge: merge the objects' own trees into the untouched static tree [Naylor1990] (object_merge.h).
// torres: objects' own trees in the static tree's cells, kept apart by separating planes, moved in
//   place while they stay in their cells [Torres1990] (torres.h).
// All but rebuild keep a mutable tree (dynamic_tree.h) and build strict trees only; tree() is then
// a snapshot taken outside the timed update.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dynamic/update_work.h"
#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/build.h"
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

// The strategies by name, each building with `splitter` (the caller picks the heuristic) and
// `build`; merge and torres build the objects' own trees with `object_splitter`. Throws UsageError
// naming the known strategies for another name, and for options a strategy cannot honour.
std::unique_ptr<Updater> make_updater(std::string_view strategy, std::unique_ptr<Splitter> splitter,
                                      std::unique_ptr<Splitter> object_splitter, const BuildOptions& build = {});
std::vector<std::string> updater_names();

}  // namespace bsp
