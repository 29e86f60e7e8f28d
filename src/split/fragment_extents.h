#pragma once
// The axis-aligned extents of a node's fragments, what the spatial front ends (`octree`, `sah`)
// place their planes by: each fragment's interval per axis and the box of all of them.
#include <cstddef>
#include <vector>

#include "geometry/vec3.h"
#include "split/splitter.h"

namespace bsp {

class FragmentExtents {
 public:
  // O(V) over the node's vertices; the arrays are reused from node to node.
  void measure(const SplitContext& ctx);

  std::size_t size() const { return lo_.size(); }
  const Vec3& lo(std::size_t i) const { return lo_[i]; }
  const Vec3& hi(std::size_t i) const { return hi_[i]; }
  const Box& box() const { return box_; }

  // Whether some fragment lies wholly behind the plane axis = x and some wholly in front, farther
  // than eps: the plane then leaves each child fewer fragments than the node, so a build ends.
  bool parts(int axis, double x, double eps) const;

 private:
  std::vector<Vec3> lo_, hi_;
  Box box_;
};

}  // namespace bsp
