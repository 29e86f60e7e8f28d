#include "validate/exact_invariants.h"

#include <utility>

namespace bsp {

namespace {

class Checker {
 public:
  explicit Checker(const ExactTree& t) : t_(t) {}

  ExactInvariantReport run() {
    const Tree& tree = t_.tree;
    if (tree.fragments.size() != t_.fragments.size() || tree.fragment_plane.size() != t_.fragments.size()) {
      fail("view, fragment planes and plane polygons differ in number");
      return std::move(report_);  // fragments_of() ranges would run past the plane polygons
    }
    check_conservation();
    if (tree.empty()) return std::move(report_);
    // A tree whose structure is broken cannot be walked safely: stop at its first structural fault.
    if (!check_structure()) return std::move(report_);
    for (std::uint32_t f = 0; f < t_.fragments.size(); ++f)
      if (!is_valid(t_.fragments[f], report_.predicates)) fail("fragment " + std::to_string(f) + " is not a valid plane polygon");
    check_nodes();
    return std::move(report_);
  }

 private:
  void fail(std::string what) {
    ++report_.violations;
    if (report_.first_problems.size() < kMaxProblems) report_.first_problems.push_back(std::move(what));
  }

  // Pre-order with the front child first: walking the tree so must meet nodes 0, 1, 2, ...; the
  // fragment ranges start at 0, never decrease and stay within the fragments. Records each node's
  // parent and side for check_nodes. False at the first fault.
  bool check_structure() {
    const std::uint64_t before = report_.violations;
    const auto& nodes = t_.tree.nodes;
    parent_.assign(nodes.size(), kNull);
    parent_front_.assign(nodes.size(), true);
    std::vector<std::uint32_t> stack{0};
    std::uint32_t expected = 0;
    while (!stack.empty()) {
      const std::uint32_t n = stack.back();
      stack.pop_back();
      if (n >= nodes.size() || n != expected++) {
        fail("nodes are not in pre-order at node " + std::to_string(n));
        return false;
      }
      for (const bool front : {false, true}) {
        const std::uint32_t child = front ? nodes[n].front : nodes[n].back;
        if (child == kNull) continue;
        if (child < nodes.size()) {
          parent_[child] = n;
          parent_front_[child] = front;
        }
        stack.push_back(child);
      }
    }
    if (expected != nodes.size()) {
      fail("unreachable nodes");
      return false;
    }
    const auto fragments = static_cast<std::uint32_t>(t_.fragments.size());
    const std::size_t planes = 2 * t_.planes.size();
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
      const bool internal = nodes[n].front != kNull || nodes[n].back != kNull;
      if ((internal && nodes[n].plane == kNull) || (nodes[n].plane != kNull && nodes[n].plane >= planes))
        fail("node " + std::to_string(n) + " has no plane or one past the pool");
    }
    for (std::uint32_t f = 0; f < fragments; ++f)
      if (t_.tree.fragment_plane[f] >= planes) fail("fragment " + std::to_string(f) + "'s plane is past the pool");
    if (nodes[0].first != 0) fail("the root's fragments do not start at 0");
    for (std::uint32_t n = 0; n < nodes.size(); ++n)
      if (nodes[n].first > fragments || (n + 1 < nodes.size() && nodes[n].first > nodes[n + 1].first))
        fail("fragment ranges out of order or out of range at node " + std::to_string(n));
    return report_.violations == before;
  }

  // Each fragment against its own node (storage) and against every ancestor (separation), found by
  // walking the parent links up: O(depth) per fragment and no copy of the path.
  void check_nodes() {
    const auto& nodes = t_.tree.nodes;
    for (std::uint32_t n = 0; n < nodes.size(); ++n) {
      const FragmentRange r = t_.tree.fragments_of(n);
      for (std::uint32_t f = r.begin; f < r.end; ++f) {
        check_storage(nodes[n], f, r);
        for (std::uint32_t child = n, up = parent_[n]; up != kNull; child = up, up = parent_[up])
          check_side(f, parent_front_[child] ? nodes[up].plane : PlanePool::flip(nodes[up].plane));
      }
    }
  }

  void check_storage(const Node& n, std::uint32_t f, const FragmentRange& r) {
    const GridPlane support = t_.fragments.support(f);
    if (n.plane != kNull) {
      const GridPlane p = canonical(t_.plane(n.plane));
      const GridPlane s = canonical(support);
      if (!(s == p || s == -p)) fail("fragment " + std::to_string(f) + " is not in its node's plane");
      return;
    }
    for (std::uint32_t g = r.begin; g < r.end; ++g)
      if (g != f && !in_front_or_on(f, t_.fragments.support(g)))
        fail("coarse leaf fragment " + std::to_string(f) + " is behind fragment " + std::to_string(g));
  }

  void check_side(std::uint32_t f, std::uint32_t plane) {
    if (!in_front_or_on(f, t_.plane(plane))) fail("fragment " + std::to_string(f) + " is on the wrong side of an ancestor");
  }

  bool in_front_or_on(std::uint32_t f, const GridPlane& plane) {
    const PlanePolygon poly = t_.fragments[f];
    for (std::size_t i = 0; i < poly.size(); ++i)
      if (side_of_vertex(poly.support, poly.before(i), poly.after(i), plane, report_.predicates) < 0) return false;
    return true;
  }

  void check_conservation() {
    const BuildStats& s = t_.tree.stats;
    const std::uint64_t usable = s.n_input - s.dropped_input + s.triangulated_extra;
    if (t_.fragments.size() != usable + s.splits)
      fail("fragments " + std::to_string(t_.fragments.size()) + " != usable inputs " + std::to_string(usable) +
           " + splits " + std::to_string(s.splits));
    if (s.dropped_slivers != 0) fail("the exact build dropped a sliver");
  }

  static constexpr std::size_t kMaxProblems = 10;  // reported by text; all are counted

  const ExactTree& t_;
  ExactInvariantReport report_;
  std::vector<std::uint32_t> parent_;  // by node, from check_structure
  std::vector<bool> parent_front_;     // whether the node is its parent's front child
};

}  // namespace

ExactInvariantReport check_exact_invariants(const ExactTree& tree) { return Checker(tree).run(); }

}  // namespace bsp
