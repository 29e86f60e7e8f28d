#include "dynamic/updater.h"

#include "common/errors.h"
#include "dynamic/rebuild.h"

namespace bsp {

std::vector<std::string> updater_names() { return {"rebuild"}; }

std::unique_ptr<Updater> make_updater(std::string_view strategy, std::unique_ptr<Splitter> splitter,
                                      const BuildOptions& build) {
  if (strategy == "rebuild") return std::make_unique<RebuildUpdater>(std::move(splitter), build);
  std::string known;
  for (const auto& n : updater_names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown update strategy '" + std::string(strategy) + "' (known: " + known + ")");
}

}  // namespace bsp
