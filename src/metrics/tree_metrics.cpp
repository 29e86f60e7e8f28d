#include "metrics/tree_metrics.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

namespace bsp {

namespace {

void measure_shape(const Tree& tree, TreeMetrics& m) {
  const std::size_t n = tree.nodes.size();
  // Nodes are stored in pre-order: every parent precedes its children.
  std::vector<std::uint32_t> depth(n, 1);
  for (std::size_t i = 0; i < n; ++i)
    for (auto c : {tree.nodes[i].front, tree.nodes[i].back})
      if (c != kNull) depth[c] = depth[i] + 1;
  std::vector<std::uint64_t> subtree(n, 0);
  double leaf_depth_sum = 0, frag_depth_sum = 0, balance_sum = 0;
  std::uint64_t internal = 0;
  for (std::size_t i = n; i-- > 0;) {
    const Node& node = tree.nodes[i];
    const std::uint64_t f = node.front == kNull ? 0 : subtree[node.front];
    const std::uint64_t b = node.back == kNull ? 0 : subtree[node.back];
    const std::uint32_t count = tree.fragments_of(static_cast<std::uint32_t>(i)).size();
    subtree[i] = f + b + count;
    m.max_depth = std::max(m.max_depth, depth[i]);
    frag_depth_sum += static_cast<double>(depth[i]) * count;
    if (!node.has_children()) {
      ++m.leaves;
      leaf_depth_sum += depth[i];
    } else if (f + b > 0) {
      ++internal;
      balance_sum += std::abs(static_cast<double>(f) - static_cast<double>(b)) / static_cast<double>(f + b);
    }
  }
  m.mean_depth = m.leaves ? leaf_depth_sum / static_cast<double>(m.leaves) : 0.0;
  m.fragment_weighted_depth = m.fragments ? frag_depth_sum / static_cast<double>(m.fragments) : 0.0;
  m.mean_balance = internal ? balance_sum / static_cast<double>(internal) : 0.0;
}

void add_costs(const TreeMetrics& m, nlohmann::json& out) {
  out.update({{"cell_margin", m.cell_margin},
              {"e_point", m.expected.e_point},
              {"e_line", m.expected.e_line},
              {"root_cell_volume", m.expected.root_volume},
              {"root_cell_area", m.expected.root_area},
              {"views", m.views},
              {"full_nodes_visited", m.traversal.full_nodes_visited},
              {"full_plane_evals", m.traversal.full_plane_evals},
              {"culled_nodes_visited", m.traversal.culled_nodes_visited},
              {"culled_plane_evals", m.traversal.culled_plane_evals},
              {"culled_fragments_emitted", m.traversal.culled_fragments_emitted},
              {"rays", m.rays},
              {"ray_seed", m.ray_seed},
              {"ray_nodes_visited", m.ray.nodes_visited},
              {"ray_fragment_tests", m.ray.fragment_tests},
              {"ray_hit_fraction", m.ray.hit_fraction},
              {"ray_max_nodes_visited", m.ray.max_nodes_visited},
              {"point_plane_tests", m.ray.point_plane_tests}});
}

}  // namespace

TreeMetrics measure_tree(const Tree& tree) {
  TreeMetrics m;
  m.n_input = tree.stats.n_input;
  m.fragments = tree.fragments.size();
  m.splits = tree.stats.splits;
  m.dropped_input = tree.stats.dropped_input;
  m.dropped_slivers = tree.stats.dropped_slivers;
  m.nodes = tree.nodes.size();
  m.bytes = tree.bytes();
  m.build_seconds = tree.stats.build_seconds;
  measure_shape(tree, m);
  return m;
}

TreeMetrics measure_tree(const Tree& tree, const MetricsSettings& settings) {
  TreeMetrics m = measure_tree(tree);
  m.costs_measured = true;
  m.cell_margin = settings.cell_margin;
  m.expected = expected_costs(tree, settings.cell_margin);
  m.views = settings.views;
  m.traversal = traversal_cost(tree, metric_views(tree.bounds, settings.views));
  m.rays = settings.rays;
  m.ray_seed = settings.seed;
  m.ray = ray_cost(tree, metric_rays(tree.bounds, settings.rays, settings.seed));
  return m;
}

nlohmann::json to_json(const TreeMetrics& m) {
  nlohmann::json out = {{"n_input", m.n_input},
                        {"fragments", m.fragments},
                        {"splits", m.splits},
                        {"dropped_input", m.dropped_input},
                        {"dropped_slivers", m.dropped_slivers},
                        {"nodes", m.nodes},
                        {"leaves", m.leaves},
                        {"bytes", m.bytes},
                        {"max_depth", m.max_depth},
                        {"mean_depth", m.mean_depth},
                        {"fragment_weighted_depth", m.fragment_weighted_depth},
                        {"mean_balance", m.mean_balance},
                        {"build_seconds", m.build_seconds}};
  if (m.costs_measured) add_costs(m, out);
  return out;
}

}  // namespace bsp
