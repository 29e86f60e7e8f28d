#include "solid/view_cull.h"

#include "geometry/convex_loop.h"
#include "solid/merge.h"

namespace bsp {

SolidTree convex_volume_tree(std::span<const Plane> outward, const Box& box) {
  SolidTree t;
  t.box = box;
  t.tol = Tolerance::for_extent(box.diagonal());
  // Built from the last plane up: each node's back child is the next plane's node.
  Ref inside = kIn;
  for (std::size_t i = outward.size(); i-- > 0;) inside = t.add_node(outward[i], 0, kOut, inside);
  t.root = inside;
  compute_subhyperplanes(t);
  return t;
}

std::vector<Plane> frustum_planes(const Frustum& f) {
  // corners(): near then far, each (-x,-y), (-x,+y), (+x,-y), (+x,+y) in the image axes.
  const auto c = f.corners();
  const Vec3 centre = (c[0] + c[7]) * 0.5;
  const auto facing_out = [&](const Vec3& a, const Vec3& b, const Vec3& d) {
    Plane p = Plane::through(cross(b - a, d - a), a);
    return p.distance(centre) > 0 ? p.flipped() : p;
  };
  return {facing_out(c[0], c[1], c[2]), facing_out(c[4], c[5], c[6]), facing_out(c[0], c[1], c[4]),
          facing_out(c[2], c[3], c[6]), facing_out(c[0], c[2], c[4]), facing_out(c[1], c[3], c[5])};
}

namespace {

// One step of the walk: visit a scene node with the part of the volume inside its region, or emit
// the fragments on its plane once its far side is done.
struct Step {
  std::uint32_t node;
  bool emit_only;
  Ref volume;           // the volume's part inside the node's region (a Ref into the work tree)
  std::uint32_t depth;  // of the node; path[0, depth) are its ancestors' half-spaces towards it
  Plane towards;
};

}  // namespace

std::vector<std::uint32_t> merged_visibility_order(const Tree& scene, const Frustum& frustum,
                                                   MergeCullCounters* counters) {
  std::vector<std::uint32_t> out;
  MergeCullCounters c;
  if (scene.empty()) {
    if (counters) *counters = c;
    return out;
  }
  Box box = scene.bounds;
  for (const Vec3& p : frustum.corners()) box.add(p);
  box = box.enlarged(kSolidBoxMargin);
  const std::vector<Plane> planes = frustum_planes(frustum);
  SolidTree work = convex_volume_tree(planes, box);
  MergeStats stats;
  Partitioner partitioner(work, stats);
  const double eps = scene.tol.plane_eps;
  const auto emit = [&](std::uint32_t i) { out.push_back(i); };
  std::vector<Step> stack{{0, false, work.root, 0, {}}};
  std::vector<Plane> path;
  std::vector<Vec3> loop, front, back;
  while (!stack.empty()) {
    const Step s = stack.back();
    stack.pop_back();
    const Node& node = scene.nodes[s.node];
    if (s.emit_only) {
      const FragmentRange r = scene.fragments_of(s.node);
      for (std::uint32_t i = r.begin; i < r.end; ++i) emit(i);
      c.traversal.fragments_emitted += r.size();
      continue;
    }
    ++c.traversal.nodes_visited;
    if (node.is_cell_leaf()) {
      detail::emit_convex_leaf(scene, s.node, frustum.eye, Order::BackToFront, emit, c.traversal);
      continue;
    }
    path.resize(s.depth);
    if (s.depth > 0) path.back() = s.towards;
    const Plane& h = scene.planes[node.plane];
    Ref in_front = s.volume, in_back = s.volume;
    if (s.volume == kIn) {
      ++c.inside_nodes;
    } else {
      // shp(v): h inside the box, cut by every ancestor's half-space.
      loop = plane_in_box(h, box);
      for (const Plane& p : path) {
        if (loop.empty()) break;
        split_loop(loop, p, 0.0, front, back);
        loop.swap(front);
      }
      if (!loop.empty()) {
        const Partitioner::Parts parts = partitioner.partition(s.volume, work.loops.add(loop), h);
        in_front = parts.plus;
        in_back = parts.minus;
      }
    }
    const auto child = [&](std::uint32_t index, Ref volume, const Plane& towards) {
      if (index != kNull && volume != kOut) stack.push_back({index, false, volume, s.depth + 1, towards});
    };
    if (in_front == kOut || in_back == kOut) {  // the volume stays on one side within the region
      child(node.front, in_front, h);
      child(node.back, in_back, h.flipped());
      continue;
    }
    ++c.traversal.plane_evals;
    const bool eye_in_front = h.distance(frustum.eye) >= -eps;
    // The near side is pushed first, so the far side, pushed last, is walked first.
    if (eye_in_front) child(node.front, in_front, h);
    else child(node.back, in_back, h.flipped());
    if (scene.fragments_of(s.node).size() > 0) stack.push_back({s.node, true, kOut, s.depth, {}});
    if (eye_in_front) child(node.back, in_back, h.flipped());
    else child(node.front, in_front, h);
  }
  c.partition_nodes = stats.partition_nodes;
  c.shp_splits = stats.shp_splits;
  c.inconsistent = stats.inconsistent;
  if (counters) *counters = c;
  return out;
}

}  // namespace bsp
