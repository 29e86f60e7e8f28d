#pragma once
// Back-to-front traversal culled by a view frustum ([AlphaBSP] "Traversing BSP Tree"; [Chrysanthou §5]
// does the same by merging with the view volume's tree). The frustum is convex, the convex hull of
// its eight corners, so when every corner lies strictly on one side of a node's plane the other
// subtree and the fragments stored on the plane lie wholly outside it and are skipped. Otherwise
// both subtrees are visited in the order of traverse.h (far side, the node's own fragments, near
// side), so the culled sequence is a subsequence of the full back-to-front order. Culling is
// conservative: every fragment meeting the frustum is emitted; some outside it may be too. Runs on
// an explicit stack.
#include <array>
#include <cstdint>
#include <vector>

#include "tree/traverse.h"
#include "tree/tree.h"

namespace bsp {

// A perspective view volume: the points p whose depth z = look·(p - eye) lies in [near, far] and
// whose offsets along the image axes satisfy |right·(p - eye)| <= z tan(fov_x/2) and
// |up'·(p - eye)| <= z tan(fov_y/2), where right = look × up and up' = right × look (both
// normalised; `up` need only not be parallel to `look`). Angles are full fields of view in radians,
// in (0, pi); 0 < near < far.
struct Frustum {
  Vec3 eye;
  Vec3 look{0, 0, -1};  // viewing direction (normalised on use)
  Vec3 up{0, 1, 0};
  double fov_x = 1.0;
  double fov_y = 1.0;
  double near = 0.01;
  double far = 100.0;

  // Near-plane corners, then far-plane corners.
  std::array<Vec3, 8> corners() const;
  // True when p is inside the frustum shrunk by `margin` (so points within `margin` of its
  // boundary count as outside; a negative margin grows it).
  bool contains(const Vec3& p, double margin) const;
};

namespace detail {

// FrontOnly (BackOnly) when every corner of the frustum lies strictly in front of (behind) the plane
// beyond eps, else Both; stops as soon as it has seen both sides. Adds the corners tested to `evals`.
Visit frustum_side(const Plane& plane, const std::array<Vec3, 8>& corners, double eps, std::uint64_t& evals);

}  // namespace detail

// Calls emit(fragment index) for the fragments of the cells the frustum may meet, back to front as
// seen from frustum.eye. Counters: nodes visited, point-plane evaluations (corners tested, the eye
// where the frustum straddles a plane, one per fragment of a visited coarse leaf), fragments emitted.
template <class Emit>
TraversalCounters traverse_culled(const Tree& tree, const Frustum& frustum, Emit&& emit) {
  const std::array<Vec3, 8> corners = frustum.corners();
  const double eps = tree.tol.plane_eps;
  return detail::walk(tree, frustum.eye, Order::BackToFront, emit, [&](const Plane& plane, TraversalCounters& c) {
    return detail::frustum_side(plane, corners, eps, c.plane_evals);
  });
}

std::vector<std::uint32_t> culled_visibility_order(const Tree& tree, const Frustum& frustum,
                                                   TraversalCounters* counters = nullptr);

}  // namespace bsp
