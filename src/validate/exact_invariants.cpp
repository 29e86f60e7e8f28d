#include "validate/exact_invariants.h"

#include <utility>

namespace bsp {

namespace {

class Checker {
 public:
  explicit Checker(const ExactTree& t) : t_(t) {}

  ExactInvariantReport run() {
    const Tree& tree = t_.tree;
    if (tree.fragments.size() != t_.fragments.size()) fail("view and plane polygons differ in number");
    check_conservation();
    if (tree.empty()) return std::move(report_);
    check_structure();
    for (std::uint32_t f = 0; f < t_.fragments.size(); ++f)
      if (!is_valid(t_.fragments[f], report_.predicates)) fail("fragment " + std::to_string(f) + " is not a valid plane polygon");
    check_nodes();
    return std::move(report_);
  }

 private:
  void fail(std::string what) {
    ++report_.violations;
    if (report_.first_problems.size() < 10) report_.first_problems.push_back(std::move(what));
  }

  // Pre-order with the front child first: walking the tree so must meet nodes 0, 1, 2, ...
  void check_structure() {
    const auto& nodes = t_.tree.nodes;
    std::vector<std::uint32_t> stack{0};
    std::uint32_t expected = 0;
    while (!stack.empty()) {
      const std::uint32_t n = stack.back();
      stack.pop_back();
      if (n >= nodes.size() || n != expected++) {
        fail("nodes are not in pre-order at node " + std::to_string(n));
        return;
      }
      if (nodes[n].back != kNull) stack.push_back(nodes[n].back);
      if (nodes[n].front != kNull) stack.push_back(nodes[n].front);
    }
    if (expected != nodes.size()) fail("unreachable nodes");
    for (std::uint32_t n = 0; n + 1 < nodes.size(); ++n)
      if (nodes[n].first > nodes[n + 1].first) fail("fragment ranges out of order at node " + std::to_string(n));
  }

  // Each fragment against its own node (storage) and against every ancestor (separation): the walk
  // carries the oriented planes of the path, each with the cell in front of it.
  void check_nodes() {
    const auto& nodes = t_.tree.nodes;
    struct Pending {
      std::uint32_t node;
      std::vector<std::uint32_t> path;  // oriented pooled planes: the subtree is in front of each
    };
    std::vector<Pending> stack{{0, {}}};
    while (!stack.empty()) {
      Pending p = std::move(stack.back());
      stack.pop_back();
      const Node& n = nodes[p.node];
      const FragmentRange r = t_.tree.fragments_of(p.node);
      for (std::uint32_t f = r.begin; f < r.end; ++f) {
        check_storage(n, f, r);
        for (auto plane : p.path) check_side(f, plane);
      }
      if (n.plane == kNull) continue;
      if (n.back != kNull) {
        std::vector<std::uint32_t> path = p.path;
        path.push_back(PlanePool::flip(n.plane));
        stack.push_back({n.back, std::move(path)});
      }
      if (n.front != kNull) {
        p.path.push_back(n.plane);
        stack.push_back({n.front, std::move(p.path)});
      }
    }
  }

  void check_storage(const Node& n, std::uint32_t f, const FragmentRange& r) {
    const GridPlane& support = t_.fragments[f].support;
    if (n.plane != kNull) {
      const GridPlane p = canonical(t_.plane(n.plane));
      const GridPlane s = canonical(support);
      if (!(s == p || s == -p)) fail("fragment " + std::to_string(f) + " is not in its node's plane");
      return;
    }
    for (std::uint32_t g = r.begin; g < r.end; ++g)
      if (g != f && !in_front_or_on(f, t_.fragments[g].support))
        fail("coarse leaf fragment " + std::to_string(f) + " is behind fragment " + std::to_string(g));
  }

  void check_side(std::uint32_t f, std::uint32_t plane) {
    if (!in_front_or_on(f, t_.plane(plane))) fail("fragment " + std::to_string(f) + " is on the wrong side of an ancestor");
  }

  bool in_front_or_on(std::uint32_t f, const GridPlane& plane) {
    const PlanePolygon& poly = t_.fragments[f];
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

  const ExactTree& t_;
  ExactInvariantReport report_;
};

}  // namespace

ExactInvariantReport check_exact_invariants(const ExactTree& tree) { return Checker(tree).run(); }

}  // namespace bsp
