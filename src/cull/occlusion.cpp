#include "cull/occlusion.h"

#include <algorithm>
#include <array>

#include "geometry/convex_loop.h"
#include "geometry/polygon.h"

namespace bsp {

namespace {

using Ref = std::int32_t;  // a beam node (>= 0) or a leaf
constexpr Ref kOutLeaf = -1;
constexpr Ref kInLeaf = -2;

struct BeamNode {
  Plane plane;  // through the eye
  Ref front, back;
};

class Beam {
 public:
  Beam(const Vec3& eye, double plane_eps, OcclusionCounters& c) : eye_(eye), eps_(plane_eps), c_(c) {}

  bool empty() const { return root_ == kOutLeaf; }
  std::size_t size() const { return nodes_.size(); }

  // Filters a convex loop down the beam; true when some piece reaches an OUT leaf. With merge,
  // every OUT leaf reached is replaced by the beam of the piece that reached it.
  bool filter(std::span<const Vec3> loop, bool merge) {
    if (edge_on(loop)) return true;
    winding_ = winding(loop);
    bool visible = false;
    stack_.clear();
    stack_.push_back({root_, -1, true, {loop.begin(), loop.end()}});
    while (!stack_.empty()) {
      Item item = std::move(stack_.back());
      stack_.pop_back();
      if (item.at == kInLeaf) continue;
      if (item.at == kOutLeaf) {
        visible = true;
        if (!merge) return true;
        const Ref b = beam_of(item.piece);
        if (b != kOutLeaf) {
          link(item.parent, item.front, b);
          ++c_.beam_merges;
        }
        continue;
      }
      ++c_.beam_steps;
      descend(std::move(item));
    }
    return visible;
  }

 private:
  struct Item {
    Ref at;
    Ref parent;  // -1: the root
    bool front;
    std::vector<Vec3> piece;
  };

  // A loop whose plane passes within the band of the eye is seen edge-on: it covers no direction,
  // and every beam plane would have it within the band on both sides.
  bool edge_on(std::span<const Vec3> loop) const {
    const Vec3 normal = newell_normal(loop);
    const double len = length(normal);
    if (len == 0) return true;
    return std::abs(dot(normal / len, eye_ - loop.front())) <= band_();
  }
  // +1 when the eye sees the loop's vertices counter-clockwise (it is in front of the loop's
  // plane), else -1. Pieces keep their fragment's vertex order, so one sign orients every edge
  // plane of every piece: no test against a piece's own centroid, which a sliver piece leaves on
  // the wrong side of its long edges' planes.
  double winding(std::span<const Vec3> loop) const {
    return dot(newell_normal(loop), eye_ - loop.front()) > 0 ? 1.0 : -1.0;
  }
  double band_() const { return kBeamBand * eps_; }

  void descend(Item item) {
    const BeamNode& n = nodes_[static_cast<std::size_t>(item.at)];
    const Ref front = n.front, back = n.back, at = item.at;
    const Plane plane = n.plane;
    double lo = 1e300, hi = -1e300;
    for (const Vec3& v : item.piece) {
      const double d = plane.distance(v);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    const double b = band_();
    // Beyond the band on one side only: that side. Within it on both: both, unsplit (a piece too
    // small to tell). Beyond it on both: split.
    const bool to_front = hi > b || lo >= -b, to_back = lo < -b || hi <= b;
    if (hi > b && lo < -b) {
      ++c_.beam_splits;
      split_loop(item.piece, plane, b, front_part_, back_part_);
      // A part too thin to keep goes as the whole piece: a larger piece only makes the test
      // more conservative.
      stack_.push_back({back, at, false, back_part_.size() >= 3 ? back_part_ : item.piece});
      stack_.push_back({front, at, true, front_part_.size() >= 3 ? front_part_ : std::move(item.piece)});
      return;
    }
    if (to_back) stack_.push_back({back, at, false, item.piece});
    if (to_front) stack_.push_back({front, at, true, std::move(item.piece)});
  }

  void link(Ref parent, bool front, Ref child) {
    if (parent < 0) root_ = child;
    else (front ? nodes_[static_cast<std::size_t>(parent)].front : nodes_[static_cast<std::size_t>(parent)].back) = child;
  }

  // The piece's cone from the eye as a chain of its edge planes, IN at the end. For a
  // counter-clockwise loop seen from its front, the inside of edge (p, q) is where
  // cross(p - eye, q - eye) = cross(p - eye, q - p) is negative; the second form keeps a short edge
  // accurate (q - p of two nearby doubles is exact), where the first would cancel. A repeated
  // vertex gives no plane (its neighbours meet there); an edge pointing at the eye gives no
  // accurate one and refuses the beam (kOutLeaf): leaving its plane out would widen the cone.
  Ref beam_of(std::span<const Vec3> piece) {
    const std::size_t first = nodes_.size();
    Ref head = kInLeaf;
    for (std::size_t i = piece.size(); i-- > 0;) {
      const Vec3 &p = piece[i], &q = piece[(i + 1) % piece.size()];
      if (p == q) continue;
      const Vec3 n = cross(p - eye_, q - p) * -winding_;
      const double nl = length(n);
      if (!(nl > kMinEdgeSine * length(p - eye_) * length(q - p))) {
        nodes_.resize(first);
        ++c_.beams_refused;
        return kOutLeaf;
      }
      nodes_.push_back({Plane{n / nl, -dot(n / nl, eye_)}, head, kOutLeaf});
      head = static_cast<Ref>(nodes_.size() - 1);
    }
    return head == kInLeaf ? kOutLeaf : head;
  }

  Vec3 eye_;
  double eps_;
  double winding_ = 1;  // of the loop being filtered
  OcclusionCounters& c_;
  std::vector<BeamNode> nodes_;
  Ref root_ = kOutLeaf;
  std::vector<Item> stack_;
  std::vector<Vec3> front_part_, back_part_;
};

// The faces of the box that face the eye (at most three), as loops; empty when the eye is inside.
std::vector<std::array<Vec3, 4>> faces_towards(const Box& box, const Vec3& eye) {
  std::vector<std::array<Vec3, 4>> faces;
  if (box.contains(eye)) return faces;
  const double e[3] = {eye.x, eye.y, eye.z}, lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  for (int a = 0; a < 3; ++a) {
    if (e[a] >= lo[a] && e[a] <= hi[a]) continue;
    const double at = e[a] < lo[a] ? lo[a] : hi[a];
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const double us[4] = {lo[u], hi[u], hi[u], lo[u]}, vs[4] = {lo[v], lo[v], hi[v], hi[v]};
    std::array<Vec3, 4> f;
    for (std::size_t k = 0; k < 4; ++k) {
      double p[3];
      p[a] = at, p[u] = us[k], p[v] = vs[k];
      f[k] = {p[0], p[1], p[2]};
    }
    faces.push_back(f);
  }
  return faces;
}

}  // namespace

Occluder::Occluder(const Tree& tree)
    : tree_(tree), subtree_box_(tree.nodes.size()), subtree_fragments_(tree.nodes.size(), 0) {
  // Children come after their parent in the pre-order layout, so one backward pass suffices. Boxes
  // grow by plane_eps so that none is flat (a flat face would be a degenerate loop).
  const double m = tree.tol.plane_eps;
  for (std::size_t n = tree.nodes.size(); n-- > 0;) {
    Box& b = subtree_box_[n];
    const FragmentRange r = tree.fragments_of(static_cast<std::uint32_t>(n));
    for (std::uint32_t f = r.begin; f < r.end; ++f)
      for (const Vec3& p : tree.fragments.points(f)) b.add(p);
    for (const std::uint32_t c : {tree.nodes[n].front, tree.nodes[n].back})
      if (c != kNull) b.add(subtree_box_[c]);
    if (!b.empty()) b = {b.lo - Vec3{m, m, m}, b.hi + Vec3{m, m, m}};
    subtree_fragments_[n] = r.size();
    for (const std::uint32_t c : {tree.nodes[n].front, tree.nodes[n].back})
      if (c != kNull) subtree_fragments_[n] += subtree_fragments_[c];
  }
}

std::vector<std::uint32_t> Occluder::visible(const Frustum& view, OcclusionCounters* counters) const {
  OcclusionCounters c;
  std::vector<std::uint32_t> out;
  Beam beam(view.eye, tree_.tol.plane_eps, c);
  const std::array<Vec3, 8> corners = view.corners();
  const std::array<Vec3, 4> near_rect = {corners[0], corners[1], corners[3], corners[2]};
  const double eps = tree_.tol.plane_eps;
  std::uint32_t since_cover_test = kCoverTestInterval - 1;  // the first test follows the first insertion
  bool stop = false;
  // The view volume starts at the near plane: what lies before it is clipped away, so it neither
  // shows nor hides anything. A fragment is filtered as its part beyond the near plane.
  const Vec3 look = normalize(view.look);
  const Plane near_plane{look, -(dot(look, view.eye) + view.near)};
  std::vector<Vec3> beyond, before;
  auto emit = [&](std::uint32_t i) {
    if (stop) return;
    ++c.fragments_tested;
    std::span<const Vec3> piece = tree_.fragments.points(i);
    if (!in_front_or_on(piece, near_plane, 0)) {
      split_loop(piece, near_plane, 0, beyond, before);
      if (beyond.size() < 3) {
        ++c.fragments_clipped;
        return;
      }
      piece = beyond;
    }
    if (!beam.filter(piece, true)) {
      ++c.fragments_hidden;
      return;
    }
    out.push_back(i);
    if (++since_cover_test < kCoverTestInterval) return;
    since_cover_test = 0;
    if (!beam.filter(near_rect, false)) stop = c.covered = true;
  };
  const auto hidden = [&](std::uint32_t n) {
    if (beam.empty() || subtree_fragments_[n] < kMinSubtreeTest) return false;
    const std::vector<std::array<Vec3, 4>> faces = faces_towards(subtree_box_[n], view.eye);
    if (faces.empty()) return false;
    ++c.subtrees_tested;
    for (const auto& f : faces)
      if (beam.filter(f, false)) return false;
    ++c.subtrees_culled;
    return true;
  };
  constexpr std::uint32_t kEmitOnly = 0x80000000u;
  std::vector<std::uint32_t> stack;
  if (!tree_.empty()) stack.push_back(0);
  TraversalCounters tc;
  while (!stack.empty() && !stop) {
    const std::uint32_t step = stack.back();
    stack.pop_back();
    const std::uint32_t index = step & ~kEmitOnly;
    if (step & kEmitOnly) {
      const FragmentRange r = tree_.fragments_of(index);
      for (std::uint32_t i = r.begin; i < r.end; ++i) emit(i);
      continue;
    }
    ++c.nodes_visited;
    if (hidden(index)) continue;
    const Node& node = tree_.nodes[index];
    if (node.is_cell_leaf()) {
      detail::emit_convex_leaf(tree_, index, view.eye, Order::FrontToBack, emit, tc);
      continue;
    }
    const Plane& plane = tree_.planes[node.plane];
    const detail::Visit visit = detail::frustum_side(plane, corners, eps, tc.plane_evals);
    if (visit != detail::Visit::Both) {
      const std::uint32_t only = visit == detail::Visit::FrontOnly ? node.front : node.back;
      if (only != kNull) stack.push_back(only);
      continue;
    }
    const bool eye_in_front = plane.distance(view.eye) >= -eps;
    const std::uint32_t first = eye_in_front ? node.front : node.back;
    const std::uint32_t last = eye_in_front ? node.back : node.front;
    if (last != kNull) stack.push_back(last);
    if (tree_.fragments_of(index).size() > 0) stack.push_back(step | kEmitOnly);
    if (first != kNull) stack.push_back(first);
  }
  c.fragments_emitted = out.size();
  c.beam_nodes = beam.size();
  if (counters) *counters = c;
  return out;
}

}  // namespace bsp
