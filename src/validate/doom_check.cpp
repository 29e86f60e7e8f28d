#include "validate/doom_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

namespace bsp {

namespace {

constexpr std::size_t kMaxProblems = 10;

// A directed line; points on its right have positive distance.
struct Line {
  double x, y, dx, dy, length;
  double distance(const DoomVertex& p) const { return ((p.x - x) * dy - (p.y - y) * dx) / length; }
};

std::optional<Line> make_line(double x, double y, double dx, double dy) {
  const double length = std::hypot(dx, dy);
  if (length == 0.0) return std::nullopt;
  return Line{x, y, dx, dy, length};
}

// One ancestor of a subsector: the node and the child taken (0 right, 1 left).
struct Step {
  std::size_t node;
  int side;
};

class Checker {
 public:
  Checker(const DoomMap& map, const VanillaNodes& nodes, double tolerance)
      : map_(map),
        n_(nodes),
        tolerance_(tolerance),
        valid_seg_(nodes.segs.size()),
        node_visits_(nodes.nodes.size()),
        subsector_visits_(nodes.subsectors.size()) {}

  DoomCheckReport run() {
    check_seg_references();
    check_coverage();
    walk();
    count_unreached();
    return r_;
  }

 private:
  void problem(std::size_t& counter, const std::string& message) {
    ++counter;
    if (r_.first_problems.size() < kMaxProblems) r_.first_problems.push_back(message);
  }

  const Linedef* linedef_of(const Seg& s) const {
    return s.linedef < map_.linedefs.size() ? &map_.linedefs[s.linedef] : nullptr;
  }

  void check_seg_references() {
    for (std::size_t i = 0; i < n_.segs.size(); ++i) {
      const Seg& s = n_.segs[i];
      const std::string name = "seg " + std::to_string(i);
      const Linedef* l = linedef_of(s);
      if (s.v1 >= n_.vertices.size() || s.v2 >= n_.vertices.size())
        problem(r_.bad_seg_vertices, name + ": vertex out of range");
      else if (!l)
        problem(r_.bad_seg_linedefs, name + ": linedef " + std::to_string(s.linedef) + " out of range");
      else if (s.side > 1 || l->sidenum[s.side] >= map_.sidedefs.size())
        problem(r_.bad_seg_sides,
                name + ": linedef " + std::to_string(s.linedef) + " has no side " + std::to_string(s.side));
      else
        valid_seg_[i] = true;
    }
  }

  void check_coverage() {
    std::vector<std::uint8_t> covered(n_.segs.size());
    for (std::size_t i = 0; i < n_.subsectors.size(); ++i) {
      const Subsector& s = n_.subsectors[i];
      const std::string name = "subsector " + std::to_string(i);
      if (s.count == 0) problem(r_.empty_subsectors, name + ": no segs");
      if (std::size_t{s.first} + s.count > n_.segs.size()) {
        problem(r_.bad_subsector_ranges, name + ": segs run past the last seg");
        continue;
      }
      for (std::size_t k = s.first; k < std::size_t{s.first} + s.count; ++k)
        if (covered[k]++ == 1)
          problem(r_.overlapping_segs, "seg " + std::to_string(k) + ": in more than one subsector");
    }
    for (std::size_t k = 0; k < covered.size(); ++k)
      if (covered[k] == 0) problem(r_.uncovered_segs, "seg " + std::to_string(k) + ": in no subsector");
  }

  // Depth first from the root with an explicit stack (a corrupt chain of nodes can be 32767 deep).
  void walk() {
    struct Visit {
      bool leaf;
      std::size_t index;
      std::size_t depth;  // path length down to this child
      Step from;
    };
    if (n_.nodes.empty() && n_.subsectors.empty()) return;
    std::vector<Visit> stack{{n_.nodes.empty(), n_.nodes.empty() ? 0 : n_.nodes.size() - 1, 0, {}}};
    std::vector<Step> path;
    while (!stack.empty()) {
      const Visit v = stack.back();
      stack.pop_back();
      path.resize(v.depth);
      if (v.depth > 0) path.back() = v.from;
      if (v.leaf) {
        if (subsector_visits_[v.index]++ == 0) check_leaf(v.index, path);
        continue;
      }
      if (node_visits_[v.index]++ > 0) continue;
      for (int side = 0; side < 2; ++side) {
        const std::uint16_t child = n_.nodes[v.index].child[side];
        if (child_in_range(v.index, side))
          stack.push_back({(child & kSubsectorChild) != 0,
                           static_cast<std::size_t>(child & ~kSubsectorChild),
                           v.depth + 1,
                           {v.index, side}});
      }
    }
  }

  bool child_in_range(std::size_t node, int side) {
    const std::uint16_t child = n_.nodes[node].child[side];
    const std::size_t index = child & ~kSubsectorChild;
    const bool leaf = child & kSubsectorChild;
    if (index < (leaf ? n_.subsectors.size() : n_.nodes.size())) return true;
    problem(r_.bad_children, "node " + std::to_string(node) + ": child " + std::to_string(side) + " is " +
                                 (leaf ? "subsector " : "node ") + std::to_string(index) + ", out of range");
    return false;
  }

  void count_unreached() {
    for (std::size_t i = 0; i < node_visits_.size(); ++i)
      count_visits(node_visits_[i], "node " + std::to_string(i), r_.unreachable_nodes, r_.repeated_nodes);
    for (std::size_t i = 0; i < subsector_visits_.size(); ++i)
      count_visits(subsector_visits_[i], "subsector " + std::to_string(i), r_.unreachable_subsectors,
                   r_.repeated_subsectors);
  }

  void count_visits(std::size_t visits, const std::string& name, std::size_t& unreached, std::size_t& repeated) {
    if (visits == 0) problem(unreached, name + ": not reached from the root");
    if (visits > 1) problem(repeated, name + ": reached " + std::to_string(visits) + " times from the root");
  }

  // The valid segs of subsector `ss` whose run is in range.
  std::vector<std::size_t> leaf_segs(std::size_t ss) const {
    const Subsector& s = n_.subsectors[ss];
    std::vector<std::size_t> segs;
    if (std::size_t{s.first} + s.count > n_.segs.size()) return segs;
    for (std::size_t k = s.first; k < std::size_t{s.first} + s.count; ++k)
      if (valid_seg_[k]) segs.push_back(k);
    return segs;
  }

  void check_leaf(std::size_t ss, const std::vector<Step>& path) {
    const std::vector<std::size_t> segs = leaf_segs(ss);
    for (const std::size_t k : segs) check_sides(k, path);
    check_convex(segs);
    check_one_sector(ss, segs);
  }

  std::optional<Line> partition(std::size_t node) {
    const NodeRecord& p = n_.nodes[node];
    const auto line = make_line(p.x, p.y, p.dx, p.dy);
    if (!line && degenerate_seen_.insert(node).second)
      problem(r_.degenerate_partitions, "node " + std::to_string(node) + ": partition has zero length");
    return line;
  }

  void check_sides(std::size_t k, const std::vector<Step>& path) {
    const Seg& s = n_.segs[k];
    double worst = 0.0;
    std::size_t worst_node = 0;
    for (const Step& step : path) {
      const auto line = partition(step.node);
      if (!line) continue;
      for (const std::uint16_t v : {s.v1, s.v2}) {
        const double d = line->distance(n_.vertices[v]);
        const double wrong = step.side == 0 ? -d : d;
        if (wrong > worst) worst = wrong, worst_node = step.node;
      }
    }
    r_.worst_side_distance = std::max(r_.worst_side_distance, worst);
    if (worst > tolerance_)
      problem(r_.wrong_side_segs, "seg " + std::to_string(k) + ": an endpoint is " + std::to_string(worst) +
                                      " units on the wrong side of node " + std::to_string(worst_node) +
                                      "'s partition");
  }

  // The line of seg k's linedef, running the way the seg faces (its sector on the right).
  std::optional<Line> seg_line(std::size_t k) const {
    const Seg& s = n_.segs[k];
    const Linedef& l = map_.linedefs[s.linedef];
    if (l.v1 >= map_.vertices.size() || l.v2 >= map_.vertices.size()) return std::nullopt;
    DoomVertex a = map_.vertices[l.v1], b = map_.vertices[l.v2];
    if (s.side == 1) std::swap(a, b);
    return make_line(a.x, a.y, static_cast<double>(b.x - a.x), static_cast<double>(b.y - a.y));
  }

  void check_convex(const std::vector<std::size_t>& segs) {
    for (const std::size_t k : segs) {
      double worst = 0.0;
      for (const std::size_t other : segs) {
        const auto line = seg_line(other);
        if (other == k || !line) continue;
        for (const std::uint16_t v : {n_.segs[k].v1, n_.segs[k].v2})
          worst = std::max(worst, -line->distance(n_.vertices[v]));
      }
      r_.worst_convexity_distance = std::max(r_.worst_convexity_distance, worst);
      if (worst > tolerance_)
        problem(r_.non_convex_segs, "seg " + std::to_string(k) + ": an endpoint is " + std::to_string(worst) +
                                        " units behind another seg of its subsector");
    }
  }

  void check_one_sector(std::size_t ss, const std::vector<std::size_t>& segs) {
    std::set<std::uint16_t> sectors;
    for (const std::size_t k : segs) {
      const Seg& s = n_.segs[k];
      sectors.insert(map_.sidedefs[map_.linedefs[s.linedef].sidenum[s.side]].sector);
    }
    if (sectors.size() > 1)
      problem(r_.mixed_sector_subsectors,
              "subsector " + std::to_string(ss) + ": segs of " + std::to_string(sectors.size()) + " sectors");
  }

  const DoomMap& map_;
  const VanillaNodes& n_;
  const double tolerance_;
  DoomCheckReport r_;
  std::vector<bool> valid_seg_;
  std::vector<std::size_t> node_visits_, subsector_visits_;
  std::set<std::size_t> degenerate_seen_;
};

}  // namespace

std::size_t DoomCheckReport::violations() const {
  return bad_children + unreachable_nodes + repeated_nodes + unreachable_subsectors + repeated_subsectors +
         bad_subsector_ranges + empty_subsectors + uncovered_segs + overlapping_segs + bad_seg_vertices +
         bad_seg_linedefs + bad_seg_sides + degenerate_partitions + wrong_side_segs + non_convex_segs +
         mixed_sector_subsectors;
}

DoomCheckReport check_doom_nodes(const DoomMap& map, const VanillaNodes& nodes, double tolerance) {
  return Checker(map, nodes, tolerance).run();
}

}  // namespace bsp
