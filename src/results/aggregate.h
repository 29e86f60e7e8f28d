#pragma once
// Per (kind, scene, heuristic, shape, and for merge runs the operation) aggregates of a report's
// runs: for each size, the mean and 95% interval over seeds of every metric and timing; across
// sizes, the growth exponent k of
// y = c * n^k fitted by least squares on log-log axes (metrics/statistics.h) to every run's
// (polygon count, value) point, with its R^2. With the same number of seeds at every size the
// exponent equals the fit through the per-size means. Growth needs two distinct sizes and
// positive values; otherwise it is null. Drawing runs also get growth_over_sizes: the fit through
// one point per size (the geometric means over seeds) with the exponent's 95% t-interval, which the
// report's theory check judges; it needs three sizes. Doom runs group by IWAD and builder label with every map
// at n = 0, so their one size summarizes the maps, and growth is fitted across maps of different sizes.
#include <nlohmann/json_fwd.hpp>

namespace bsp::results {

// `runs`: run records (record.h). Groups come out sorted by scene, heuristic, shape and the other
// scene parameters, so the result depends only on the set of runs, not their order.
nlohmann::json aggregate_runs(const nlohmann::json& runs);

}  // namespace bsp::results
