#pragma once
// The update strategies (the interface they share: dynamic/update_strategy.h) by name:
// rebuild: a full build per frame, the baseline every other strategy is measured against.
// reinsert, reinsert-each: remove the moving objects and insert them again [ChrysanthouSlater1992]
//   (reinsert.h: all removed first, or one object at a time).
// merge: merge the objects' own trees into the untouched static tree [Naylor1990] (object_merge.h).
// torres: objects' own trees in the static tree's cells, kept apart by separating planes, moved in
//   place while they stay in their cells [Torres1990] (torres.h).
// All but rebuild keep a mutable tree (dynamic_tree.h) and build strict trees only; tree() is then
// a snapshot taken outside the timed update.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "dynamic/update_strategy.h"
#include "split/splitter.h"
#include "tree/build.h"

namespace bsp {

// The strategies by name, each building with `splitter` (the caller picks the heuristic) and
// `build`; merge and torres build the objects' own trees with `object_splitter`. Throws UsageError
// naming the known strategies for another name, and for options a strategy cannot honour.
std::unique_ptr<Updater> make_updater(std::string_view strategy, std::unique_ptr<Splitter> splitter,
                                      std::unique_ptr<Splitter> object_splitter, const BuildOptions& build = {});
std::vector<std::string> updater_names();

}  // namespace bsp
