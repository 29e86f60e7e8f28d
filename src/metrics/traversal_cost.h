#pragma once
// Traversal cost per view: the work of a full back-to-front traversal (tree/traverse.h) and of one
// culled by the view frustum (tree/traverse_culled.h), averaged over a deterministic set of views.
#include <cstdint>
#include <span>
#include <vector>

#include "tree/traverse_culled.h"

namespace bsp {

// `count` views of a box with centre c and diagonal D, from the directions u_k of a Fibonacci
// sphere (k = 0..count-1: z = 1 - (2k+1)/count, azimuth k times the golden angle), alternating:
//  - even k, outside: eye c + D u_k looking at c, 60° x 45° field of view, near 0.01 D, far 2 D.
//    The box's bounding sphere spans 60° from there, so the view holds most of the scene but its
//    top and bottom are culled.
//  - odd k, inside: eye c + (size/4) ⊙ u_k (inside the box) looking along u_k, 90° x 60° field of
//    view, near 0.001 D, far D: the part of the scene beyond the eye in one direction.
// Up is +z, or +x when the look direction is within ~8° of ±z.
std::vector<Frustum> metric_views(const Box& box, std::uint32_t count);

// Means over the views (0 for no views or an empty tree). Best and worst cases, with m nodes and
// f fragments: full traversal always visits m nodes (best = worst); a culled one visits between
// about the depth of one cell (the frustum inside one cell) and m (nothing culled), and emits
// between the fragments in view and f.
struct TraversalCost {
  double full_nodes_visited = 0;
  double full_plane_evals = 0;      // one per node with a plane plus one per coarse-leaf fragment
  double culled_nodes_visited = 0;
  double culled_plane_evals = 0;    // corner, eye and coarse-leaf tests (traverse_culled.h)
  double culled_fragments_emitted = 0;
};

TraversalCost traversal_cost(const Tree& tree, std::span<const Frustum> views);

}  // namespace bsp
