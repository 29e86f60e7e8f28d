#pragma once
// Visibility orders of an exact tree (tree/exact_build.h) from an eye that is a point of the scene's
// grid, every side decided exactly: at each node, the subtree on the far side of its plane, then
// the node's fragments, then the near side [Fuchs1980]; an eye on a node's plane sees the node's
// fragments edge-on, and either order of its subtrees is right (the one of an eye in front is used).
// A coarse leaf emits its fragments as the float traversal does (tree/traverse.h): back to front,
// those whose plane has the eye in front of or on it first.
//
// Eyes may lie outside the scene's box, so their grid coordinates may exceed the grid's 2^40:
// kEyeBits bounds them, and a plane's value at such a point is computed in WideInt<3>
// (|a x| < 2^83 * 2^52, four terms below 2^138).
#include <cstdint>
#include <optional>
#include <vector>

#include "tree/exact_build.h"
#include "tree/traverse.h"

namespace bsp {

// |grid coordinate| < 2^kEyeBits for an eye: 2,600 to 5,200 scene diagonals from the box's centre
// (the grid step is 0.58 to 1.15 times 1e-12 of the diagonal).
inline constexpr int kEyeBits = 52;

// The grid point nearest p, or nullopt beyond kEyeBits.
std::optional<GridPoint> snap_eye(const Grid& grid, const Vec3& p);
// The sign of the plane's value at a point with coordinates below 2^kEyeBits.
int side_of_eye(const GridPlane& plane, const GridPoint& eye);

std::vector<std::uint32_t> exact_visibility_order(const ExactTree& tree, const GridPoint& eye, Order order);

}  // namespace bsp
