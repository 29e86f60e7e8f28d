#include "dynamic/updater.h"

#include "common/errors.h"
#include "dynamic/rebuild.h"

namespace bsp {

std::vector<std::string> updater_names() { return {"rebuild"}; }

std::unique_ptr<Updater> make_updater(std::string_view strategy, const UpdaterSettings& settings) {
  if (strategy == "rebuild") return std::make_unique<RebuildUpdater>(settings);
  std::string known;
  for (const auto& n : updater_names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown update strategy '" + std::string(strategy) + "' (known: " + known + ")");
}

}  // namespace bsp
