#pragma once
// The options that set what the query-cost metrics measure (metrics/tree_metrics.h
// MetricsSettings): [--views V] [--rays R] [--cell-margin M].
#include <cstdint>
#include <string_view>

#include "cli/args.h"
#include "metrics/tree_metrics.h"

namespace bsp::cli {

inline constexpr std::string_view kMetricsUsage = "[--views V] [--rays R] [--cell-margin M]";
inline const OptionHelps kMetricsOptions = {
    {"--views V", "eyes for the traversal costs (and, in compare, the Embree checks)"},
    {"--rays R", "random rays for the ray-shooting cost"},
    {"--cell-margin M", "root cell of the expected costs: the scene box grown by M diagonals, in (0, 10]"}};

// `seed` (the run's) seeds the metric's rays.
MetricsSettings metrics_settings_from(Args& args, std::uint64_t seed);

}  // namespace bsp::cli
