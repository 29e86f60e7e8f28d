#pragma once
// Keeping a scene's tree valid while some of its objects move: one interface for the update
// strategies a dynamic-scene run compares [Chrysanthou §8]. A frame's input is the static polygons
// (fixed for the whole run) and the moving polygons, object by object in blocks of equal size,
// always in the same layout. After every update, tree() is the tree of the static polygons and the
// moving ones at their new places, valid for any eye.
//
// rebuild: a full build per frame, the baseline every other strategy is measured against.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/polygon.h"
#include "split/splitter.h"
#include "tree/build.h"
#include "tree/tree.h"

namespace bsp {

// What one update did. Strategies that do less than a full build count their work here.
struct UpdateWork {
  double seconds = 0;                  // thread CPU seconds of the update
  std::uint64_t polygons_built = 0;    // polygons given to a build (all of them for rebuild)
};

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
// `build`; throws UsageError naming the known strategies for another name.
std::unique_ptr<Updater> make_updater(std::string_view strategy, std::unique_ptr<Splitter> splitter,
                                      const BuildOptions& build = {});
std::vector<std::string> updater_names();

}  // namespace bsp
