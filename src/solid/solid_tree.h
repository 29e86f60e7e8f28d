#pragma once
// Solid BSP trees [Thibault1987]: a partition of space whose leaf cells are labelled IN or OUT of a
// polyhedron, the representation that set operations merge [Naylor1990].
//
// Notation (as [Chrysanthou §4]): h(v) is node v's plane, r(v) its region (the cell the path from
// the root bounds, inside Thibault's bounding box), shp(v) = h(v) ∩ r(v) its sub-hyperplane, a
// convex polygon. A child link is a Ref: a node index (>= 0), or a leaf kOut / kIn.
//
// Invariants: every node's front is the side its plane's normal points to; shp(v) is clipped to
// the box and to every ancestor's half-space towards v, cut by the sign of each vertex's distance
// (tol.plane_eps only decides coplanarity); a node whose shp is empty separates nothing inside the
// box (it survives only as a tolerance artefact of merging, and reduce() removes it).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "geometry/convex_loop.h"
#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"
#include "tree/tree.h"

namespace bsp {

using Ref = std::int32_t;
inline constexpr Ref kOut = -1;
inline constexpr Ref kIn = -2;
constexpr bool is_leaf(Ref r) { return r < 0; }
constexpr Ref flip_label(Ref leaf) { return leaf == kIn ? kOut : kIn; }

// 40 bytes: what a point query reads.
struct SolidNode {
  Plane plane;
  Ref front = kOut, back = kOut;
  Ref child(bool front_side) const { return front_side ? front : back; }
};

struct SolidTree {
  std::vector<SolidNode> nodes;
  std::vector<std::uint32_t> shp;  // parallel to nodes: the loop of each node's sub-hyperplane
  LoopPool loops;
  Ref root = kOut;
  Box box;        // Thibault's bounding box: every region lies inside it
  Tolerance tol;  // from the box's diagonal

  Ref add_node(const Plane& plane, std::uint32_t loop, Ref front, Ref back);
  std::size_t bytes() const;  // nodes, sub-hyperplanes and their points (sizes, not capacities)
};

// The box two operands share, so that their sub-hyperplanes are clipped alike: both inputs' bounds
// enlarged by kSolidBoxMargin of the diagonal, so that no face lies on the box.
inline constexpr double kSolidBoxMargin = 0.05;
Box solid_box(const Box& a, const Box& b);

// A strict tree of a closed, consistently oriented mesh (faces counter-clockwise seen from outside)
// as a solid tree. Autopartitions and free planes alike: a missing child of a node is empty of the
// boundary, so it lies wholly on one side of the faces on the node's plane, outside in front of a
// face and inside behind it [Thibault1987]. Throws InputError when a coarse tree is given, or when
// a missing child's label is undecided (a node with no face on its plane, or faces of both facings:
// the mesh is not the boundary of a solid). `box` must contain the tree's bounds.
SolidTree solid_from_tree(const Tree& tree, const Box& box);

// Recomputes every shp from the planes (the box's polygon of h(v), clipped along the path).
void compute_subhyperplanes(SolidTree& solid);

enum class PointClass : std::uint8_t { Out, In, On };
// Where a point lies: a point within plane_eps of a node's plane goes down both sides, and is On when
// the two sides' labels differ (it lies on the boundary within the tolerance).
PointClass classify_point(const SolidTree& solid, const Vec3& p);

struct SolidSize {
  std::uint64_t nodes = 0;       // reachable from the root
  std::uint64_t in_leaves = 0;
  std::uint64_t out_leaves = 0;
  std::uint64_t depth = 0;       // nodes on the longest root-to-leaf path (a lone leaf: 0)
};
SolidSize solid_size(const SolidTree& solid);
// The same for any node array whose nodes have front and back Refs (the exact kernel's too).
template <class Nodes>
SolidSize solid_size_of(const Nodes& nodes, Ref root) {
  SolidSize size;
  std::vector<std::pair<Ref, std::uint64_t>> stack{{root, 0}};
  while (!stack.empty()) {
    const auto [r, depth] = stack.back();
    stack.pop_back();
    size.depth = depth > size.depth ? depth : size.depth;
    if (is_leaf(r)) {
      ++(r == kIn ? size.in_leaves : size.out_leaves);
      continue;
    }
    ++size.nodes;
    stack.push_back({nodes[r].back, depth + 1});
    stack.push_back({nodes[r].front, depth + 1});
  }
  return size;
}

// The same tree with every leaf label flipped (the complement of the solid).
SolidTree complemented(SolidTree solid);

}  // namespace bsp
