#pragma once
// The cells of a solid tree as exact polytopes: the box cut by the planes on each path, each vertex
// going by the sign of its distance (no tolerance), so the IN cells tile the solid with no sliver
// given to the wrong side. Volume and boundary both come from these cells, so they agree.
#include <vector>

#include "geometry/convex_loop.h"
#include "geometry/plane.h"
#include "solid/solid_tree.h"

namespace bsp {

// Faces counter-clockwise seen from outside, each with its outward plane (the node plane it lies
// in, facing out of the cell, or a face of the box) and the node whose plane cut it (kNoNode for the
// box's faces).
inline constexpr Ref kNoNode = -1;
struct Cell {
  LoopPool faces;
  std::vector<Plane> outward;
  std::vector<Ref> cut_by;
};

Cell box_cell(const Box& box);
// The parts in front of and behind the plane; either may come back empty (no faces). The cap is
// chained from the faces' chords across the plane, whose ends are bit-identical cut points, so its
// order is exact however close its points lie; only when rounding made a face's signs non-convex
// are the cut points ordered by angle instead.
void split_cell(const Cell& cell, const Plane& plane, Ref node, Cell& front, Cell& back);
double cell_volume(const Cell& cell);

// Calls f(cell) for every IN leaf's cell. Explicit stack; OUT subtrees are still cut, since IN
// leaves lie below them.
template <class F>
void for_each_in_cell(const SolidTree& solid, F f) {
  std::vector<std::pair<Ref, Cell>> stack;
  stack.emplace_back(solid.root, box_cell(solid.box));
  Cell front, back;
  while (!stack.empty()) {
    auto [r, cell] = std::move(stack.back());
    stack.pop_back();
    if (is_leaf(r)) {
      if (r == kIn) f(cell);
      continue;
    }
    const SolidNode& node = solid.nodes[r];
    split_cell(cell, node.plane, r, front, back);
    if (node.back != kOut && !back.outward.empty())
      stack.emplace_back(node.back, std::move(back));
    if (node.front != kOut && !front.outward.empty()) stack.emplace_back(node.front, std::move(front));
  }
}

// The sum of the IN cells' volumes: the box cut by the planes on each path, as polytopes, each
// vertex going by the sign of its distance (no tolerance: no sliver changes sides).
double solid_volume(const SolidTree& solid);

}  // namespace bsp
