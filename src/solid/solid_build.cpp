#include "solid/solid_build.h"

#include <chrono>

namespace bsp {

SolidBuild build_solid(std::span<const Polygon> polys, Splitter& splitter, const Box& box, BuildOptions options) {
  options.shape = Shape::Strict;
  const Tree tree = build_tree(polys, splitter, options);
  SolidBuild out;
  out.build = tree.stats;
  out.fragments = tree.fragments.size();
  const auto start = std::chrono::steady_clock::now();
  out.solid = solid_from_tree(tree, box);
  out.label_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bsp
