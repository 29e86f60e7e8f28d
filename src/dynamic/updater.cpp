#include "dynamic/updater.h"

#include "common/errors.h"
#include "dynamic/object_merge.h"
#include "dynamic/rebuild.h"
#include "dynamic/reinsert.h"
#include "dynamic/torres.h"

namespace bsp {

std::vector<std::string> updater_names() { return {"rebuild", "reinsert", "reinsert-each", "merge", "torres"}; }

std::unique_ptr<Updater> make_updater(std::string_view strategy, std::unique_ptr<Splitter> splitter,
                                      std::unique_ptr<Splitter> object_splitter, const BuildOptions& build) {
  if (strategy == "rebuild") return std::make_unique<RebuildUpdater>(std::move(splitter), build);
  const bool known = strategy == "reinsert" || strategy == "reinsert-each" || strategy == "merge" || strategy == "torres";
  if (known && (build.shape != Shape::Strict || build.incremental))
    throw UsageError("update strategy '" + std::string(strategy) + "' keeps a strict tree built recursively (no coarse shape, no incremental build)");
  if (strategy == "reinsert") return std::make_unique<ReinsertUpdater>(std::move(splitter), false);
  if (strategy == "reinsert-each") return std::make_unique<ReinsertUpdater>(std::move(splitter), true);
  if (strategy == "merge") return std::make_unique<MergeUpdater>(std::move(splitter), std::move(object_splitter));
  if (strategy == "torres") return std::make_unique<TorresUpdater>(std::move(splitter), std::move(object_splitter));
  std::string names;
  for (const auto& n : updater_names()) names += (names.empty() ? "" : ", ") + n;
  throw UsageError("unknown update strategy '" + std::string(strategy) + "' (known: " + names + ")");
}

}  // namespace bsp
