#include "cli/metrics_args.h"

#include <sstream>

#include "common/errors.h"

namespace bsp::cli {

namespace {

// Upper bounds that keep one metrics run within minutes on large trees.
constexpr long long kMaxViews = 1000;
constexpr long long kMaxRays = 10'000'000;
// A root cell more than this many diagonals larger than the scene measures mostly empty space.
constexpr double kMaxCellMargin = 10.0;

}  // namespace

MetricsSettings metrics_settings_from(Args& args, std::uint64_t seed) {
  MetricsSettings s;
  s.seed = seed;
  s.views = static_cast<std::uint32_t>(args.integer("--views", 1, kMaxViews).value_or(s.views));
  s.rays = static_cast<std::uint32_t>(args.integer("--rays", 0, kMaxRays).value_or(s.rays));
  s.cell_margin = args.real("--cell-margin").value_or(s.cell_margin);
  if (s.cell_margin <= 0 || s.cell_margin > kMaxCellMargin) {
    std::ostringstream msg;
    msg << "--cell-margin wants a number in (0, " << kMaxCellMargin << "], not " << s.cell_margin;
    throw UsageError(msg.str());
  }
  return s;
}

}  // namespace bsp::cli
