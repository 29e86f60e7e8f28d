// Builds a tree of a generated scene with a built-in heuristic and checks it, all through the
// installed headers and library: exit 0 when the tree holds every polygon and passes its checks.
#include <cstdio>

#include <bspbench/common/version.h>
#include <bspbench/generators/catalog.h>
#include <bspbench/metrics/tree_metrics.h>
#include <bspbench/split/registry.h>
#include <bspbench/tree/build.h>
#include <bspbench/validate/tree_invariants.h>

int main() {
  const bsp::Scene scene = bsp::make_scene("random-triangles", {{"n", "500"}, {"seed", "3"}});
  const auto splitter = bsp::make_splitter("naylor", {}, 1);
  const bsp::Tree tree = bsp::build_tree(scene.polygons, *splitter);
  const bsp::TreeMetrics m = bsp::measure_tree(tree);
  const bsp::InvariantReport check = bsp::check_tree_invariants(tree, scene.polygons);
  std::printf("bspbench %s: %zu polygons, %zu nodes, depth %u, %zu violations\n", BSPBENCH_VERSION_STRING,
              scene.polygons.size(), static_cast<std::size_t>(m.nodes), m.max_depth,
              static_cast<std::size_t>(check.violations));
  return scene.polygons.size() == 500 && m.nodes > 0 && check.ok() ? 0 : 1;
}
