#pragma once
// Tree-quality measures: a pure function from a frozen tree to a plain struct. Each field says what
// it means and its best and worst case (n = input polygons, f = fragments, m = nodes).
//
// measure_tree(tree) is cheap (size and shape, O(m + f)); measure_tree(tree, settings) adds the
// costs: Naylor's expected costs from the exact cells (expected_cost.h), the traversal work per view
// with and without frustum culling (traversal_cost.h) and the ray-shooting work (ray_cost.h).
#include <cstdint>

#include <nlohmann/json_fwd.hpp>

#include "metrics/expected_cost.h"
#include "metrics/ray_cost.h"
#include "metrics/traversal_cost.h"
#include "tree/tree.h"

namespace bsp {

struct TreeMetrics {
  // --- size
  std::uint64_t n_input = 0;    // polygons given to the build
  std::uint64_t fragments = 0;  // polygons stored in the tree. Best n (no splits); worst Θ(n²) in 3D
  std::uint64_t splits = 0;     // = fragments - n_input + dropped_input + dropped_slivers - triangulated_extra. Best 0
  std::uint64_t dropped_input = 0;    // input slivers (width < plane_eps). Best 0
  std::uint64_t dropped_slivers = 0;  // split parts narrower than plane_eps. Best 0
  std::uint64_t nodes = 0;    // strict: one per distinct plane used. Best 1 (coarse convex input); worst f
  std::uint64_t leaves = 0;   // nodes without children
  std::uint64_t bytes = 0;    // bytes the frozen tree stores (Tree::bytes: sizes, not capacities)
  // --- shape (the root has depth 1)
  std::uint32_t max_depth = 0;       // best ceil(log2(nodes+1)); worst nodes (a chain)
  double mean_depth = 0;             // mean depth of the leaves. Best about log2(nodes); worst nodes (a chain)
  double fragment_weighted_depth = 0;  // mean over fragments of the depth of the node storing them
  double mean_balance = 0;  // mean over internal nodes of |F-B|/(F+B), F and B the fragments in the
                            // front and back subtrees. Best 0 (perfectly balanced); worst 1 (chain)
  // --- cost
  double build_seconds = 0;  // wall time of the build
  // --- query costs; only measure_tree(tree, settings) fills them (costs_measured)
  bool costs_measured = false;
  ExpectedCosts expected;     // E_point, E_line over the root cell of margin `cell_margin`
  double cell_margin = 0;
  TraversalCost traversal;    // means over `views` views of metric_views(tree.bounds, views)
  std::uint32_t views = 0;
  RayCost ray;                // means over `rays` rays of metric_rays(tree.bounds, rays, ray_seed)
  std::uint32_t rays = 0;
  std::uint64_t ray_seed = 0;
};

// What measure_tree computes beyond size and shape. No globals: every knob is here.
struct MetricsSettings {
  double cell_margin = 0.01;  // root cell = tree.bounds.enlarged(cell_margin) (expected_cost.h); >= 0
  std::uint32_t views = 8;    // frustums for the traversal cost (traversal_cost.h metric_views)
  std::uint32_t rays = 1000;  // rays for the ray-shooting cost (ray_cost.h metric_rays)
  std::uint64_t seed = 1;     // seeds the rays
};

TreeMetrics measure_tree(const Tree& tree);
TreeMetrics measure_tree(const Tree& tree, const MetricsSettings& settings);
// Flat object; the query costs appear only when measured.
nlohmann::json to_json(const TreeMetrics& m);

}  // namespace bsp
