#include "validate/tree_invariants.h"

#include <cmath>
#include <vector>

#include "geometry/segment2.h"
#include "split/fragment_store.h"

namespace bsp {

namespace {

class Checker {
 public:
  Checker(const Tree& tree, InvariantReport& report) : tree_(tree), report_(report) {}

  void fail(std::string what) {
    ++report_.violations;
    if (report_.first_problems.size() < 10) report_.first_problems.push_back(std::move(what));
  }

  // 1 and 2 and 3: one depth-first walk keeping the oriented planes of the path.
  void walk() {
    const std::size_t n = tree_.nodes.size();
    std::vector<std::uint8_t> seen(n, 0);
    std::vector<std::uint8_t> covered(tree_.fragments.size(), 0);
    std::vector<std::uint32_t> path;  // oriented planes: the cell is in front of each
    struct Step { std::uint32_t node; std::uint32_t depth; std::uint32_t plane_from_parent; };
    std::vector<Step> stack;
    std::uint32_t reached = 0;
    if (n) stack.push_back({0, 0, kNull});
    while (!stack.empty()) {
      const Step s = stack.back();
      stack.pop_back();
      if (s.node >= n) { fail("child index out of range"); continue; }
      if (seen[s.node]++) { fail("node " + std::to_string(s.node) + " reached twice"); continue; }
      // Popping the front child before the back one visits the nodes in pre-order, front first.
      if (s.node != reached++) fail("node " + std::to_string(s.node) + " stored out of pre-order");
      path.resize(s.depth);
      if (s.plane_from_parent != kNull) path.push_back(s.plane_from_parent);
      const Node& node = tree_.nodes[s.node];
      check_node_fragments(s.node, node, path, covered);
      if (node.is_cell_leaf()) {
        if (node.has_children()) fail("coarse leaf " + std::to_string(s.node) + " has children");
        continue;
      }
      const std::uint32_t depth = static_cast<std::uint32_t>(path.size());
      if (node.back != kNull) stack.push_back({node.back, depth, PlanePool::flip(node.plane)});
      if (node.front != kNull) stack.push_back({node.front, depth, node.plane});
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!seen[i]) fail("node " + std::to_string(i) + " unreachable");
    for (std::size_t i = 0; i < covered.size(); ++i)
      if (covered[i] != 1) fail("fragment " + std::to_string(i) + " stored " + std::to_string(covered[i]) + " times");
  }

  // 4.
  void conservation(std::span<const Polygon> input) {
    const auto& st = tree_.stats;
    const std::uint64_t f = tree_.fragments.size();
    if (st.splits + st.n_input + st.triangulated_extra != f + st.dropped_input + st.dropped_slivers)
      fail("split identity broken: splits=" + std::to_string(st.splits) + " fragments=" + std::to_string(f));
    // Per source, what its fragments cover of it: a segment's length, a polygon's area projected
    // onto the input polygon's Newell normal. Projected areas add up exactly under splitting and
    // fanning (the Newell vector of a polygon is the sum of its pieces'), where the pieces' own
    // areas exceed the whole's when the input is bent (within plane_eps, or fanned beyond it). The
    // input's area (BuildStats::input_area) is its Newell area, the same projection.
    std::vector<Vec3> facing(input.size());
    for (std::size_t i = 0; i < input.size(); ++i) {
      const Vec3 n = input[i].verts.size() >= 3 ? newell_normal(input[i]) : Vec3{};
      if (const double len = length(n); len > 0) facing[i] = n / len;  // a zero-area input covers nothing
    }
    std::vector<double> per_source(input.size(), 0.0);
    for (const FragmentView frag : tree_.fragments) {
      const Polygon poly = frag.polygon();
      if (frag.source >= per_source.size()) {
        fail("fragment source out of range");
        continue;
      }
      per_source[frag.source] += is_segment(poly) ? measure(poly) : 0.5 * dot(newell_normal(poly), facing[frag.source]);
    }
    double total = 0;
    for (double covered : per_source) total += covered;
    const double scale = std::max(st.input_area, 1e-300);
    if (std::abs(total + st.dropped_area - st.input_area) > 1e-9 * scale)
      fail("area not conserved: fragments " + std::to_string(total) + " + dropped " +
           std::to_string(st.dropped_area) + " != input " + std::to_string(st.input_area));
    for (std::size_t i = 0; i < input.size(); ++i) {
      const double a = measure(input[i]);
      if (per_source[i] > a * (1 + 1e-9) + 1e-300)
        fail("source " + std::to_string(i) + " has more fragment area than input area");
    }
  }

 private:
  void check_node_fragments(std::uint32_t index, const Node& node, const std::vector<std::uint32_t>& path,
                            std::vector<std::uint8_t>& covered) {
    const double eps = tree_.tol.plane_eps;
    const FragmentRange r = tree_.fragments_of(index);
    if (r.begin > r.end || r.end > tree_.fragments.size()) {
      fail("node " + std::to_string(index) + " fragment range out of bounds (nodes not in pre-order)");
      return;
    }
    for (std::uint32_t i = r.begin; i < r.end; ++i) {
      ++covered[i];
      const Polygon frag = tree_.fragments[i].polygon();
      check_shape(i, frag);
      for (auto p : path)
        if (!in_front_or_on(frag, tree_.planes[p], eps) || faces_out_of(i, frag, p))
          fail("fragment " + std::to_string(i) + " at node " + std::to_string(index) + " on the wrong side of an ancestor plane");
      if (tree_.shape == Shape::Leafy && !node.is_cell_leaf())
        fail("leafy node " + std::to_string(index) + " stores fragments");
      else if (!node.is_cell_leaf() && classify(frag, tree_.planes[node.plane], eps) != Side::Coplanar)
        fail("fragment " + std::to_string(i) + " stored at node " + std::to_string(index) + " is not coplanar with it");
    }
    if (node.is_cell_leaf()) check_convex_leaf(index, r);
  }

  // Leafy trees send a fragment in a plane to the side it faces: lying in the oriented plane p of
  // its cell, it must face the same way.
  bool faces_out_of(std::uint32_t i, const Polygon& frag, std::uint32_t p) const {
    const Plane plane = tree_.planes[p];
    return tree_.shape == Shape::Leafy && classify(frag, plane, tree_.tol.plane_eps) == Side::Coplanar &&
           dot(tree_.planes[tree_.fragment_plane[i]].n, plane.n) <= 0;
  }

  // 5: no degenerate fragment: no two consecutive vertices within plane_eps, not a sliver.
  void check_shape(std::uint32_t i, const Polygon& frag) {
    for (std::size_t k = 0; k < frag.verts.size(); ++k)
      if (length(frag.verts[k].p - frag.verts[(k + 1) % frag.verts.size()].p) <= tree_.tol.plane_eps) {
        fail("fragment " + std::to_string(i) + " repeats vertex " + std::to_string(k));
        break;
      }
    if (is_thin(frag, tree_.tol.plane_eps))
      fail("fragment " + std::to_string(i) + " is a sliver (narrower than plane_eps)");
  }

  void check_convex_leaf(std::uint32_t index, FragmentRange r) {
    const double eps = tree_.tol.plane_eps;
    std::vector<Polygon> leaf;
    for (std::uint32_t i = r.begin; i < r.end; ++i) leaf.push_back(tree_.fragments[i].polygon());
    for (std::uint32_t a = r.begin; a < r.end; ++a)
      for (std::uint32_t b = r.begin; b < r.end; ++b)
        if (a != b && !bounds_cell_with(leaf[b - r.begin], b, tree_.planes[tree_.fragment_plane[a]], eps)) {
          fail("leaf " + std::to_string(index) + " is not a convex set");
          return;
        }
  }

  // Whether fragment b may share a leaf with a fragment in plane pa: in front of it or on it; in a
  // leafy tree, on it only facing the same way.
  bool bounds_cell_with(const Polygon& b, std::uint32_t bi, const Plane& pa, double eps) const {
    if (!in_front_or_on(b, pa, eps)) return false;
    return tree_.shape != Shape::Leafy || classify(b, pa, eps) != Side::Coplanar ||
           dot(tree_.planes[tree_.fragment_plane[bi]].n, pa.n) > 0;
  }

  const Tree& tree_;
  InvariantReport& report_;
};

}  // namespace

InvariantReport check_tree_invariants(const Tree& tree, std::span<const Polygon> input) {
  InvariantReport report;
  Checker checker(tree, report);
  checker.walk();
  checker.conservation(input);
  return report;
}

}  // namespace bsp
