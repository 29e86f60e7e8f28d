#pragma once
// Tree-quality measures: a pure function from a frozen tree to a plain struct. Each field says what
// it means and its best and worst case (n = input polygons, f = fragments).
#include <cstdint>

#include <nlohmann/json_fwd.hpp>

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
  std::uint64_t bytes = 0;    // memory held by the frozen tree
  // --- shape (the root has depth 1)
  std::uint32_t max_depth = 0;       // best ceil(log2(nodes+1)); worst nodes (a chain)
  double mean_depth = 0;             // mean depth of the leaves. Best about log2(nodes); worst nodes (a chain)
  double fragment_weighted_depth = 0;  // mean over fragments of the depth of the node storing them
  double mean_balance = 0;  // mean over internal nodes of |F-B|/(F+B), F and B the fragments in the
                            // front and back subtrees. Best 0 (perfectly balanced); worst 1 (chain)
  // --- cost
  double build_seconds = 0;  // wall time of the build
};

TreeMetrics measure_tree(const Tree& tree);
nlohmann::json to_json(const TreeMetrics& m);

}  // namespace bsp
