#include "io/doom_nodes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "common/errors.h"
#include "geometry/segment2.h"

namespace bsp {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint32_t kMaxNodes = 0x7FFF;  // child indices below the subsector bit
constexpr std::uint32_t kMaxSegs = 0xFFFF;

Vec3 at(const DoomVertex& v) { return {static_cast<double>(v.x), static_cast<double>(v.y), 0.0}; }

std::uint64_t key(std::int64_t x, std::int64_t y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) | static_cast<std::uint32_t>(y);
}

std::int16_t to_int16(double v, const DoomMap& map, const char* what) {
  const long r = std::lround(v);
  if (r < std::numeric_limits<std::int16_t>::min() || r > std::numeric_limits<std::int16_t>::max())
    throw InputError("map " + map.name + ": " + what + " " + std::to_string(r) + " does not fit in 16 bits");
  return static_cast<std::int16_t>(r);
}

// The linedef's direction for a side: v1 → v2 on the right side, v2 → v1 on the left.
std::pair<Vec3, Vec3> side_ends(const DoomMap& map, std::uint16_t linedef, std::uint8_t side) {
  const Linedef& l = map.linedefs[linedef];
  const Vec3 a = at(map.vertices[l.v1]), b = at(map.vertices[l.v2]);
  return side == 0 ? std::pair(a, b) : std::pair(b, a);
}

std::uint16_t binary_angle(const Vec3& from, const Vec3& to) {
  const double turns = std::atan2(to.y - from.y, to.x - from.x) / (2 * kPi);
  return static_cast<std::uint16_t>(static_cast<std::int64_t>(std::llround(turns * 65536.0)) & 0xFFFF);
}

// The map's vertices and the rounded split points, shared by every seg that ends at them.
class VertexTable {
 public:
  VertexTable(const DoomMap& map, RoundingStats& stats) : map_(map), stats_(stats), vertices_(map.vertices) {
    for (std::size_t i = 0; i < vertices_.size(); ++i) index_.try_emplace(key(vertices_[i].x, vertices_[i].y), i);
  }

  std::uint16_t of(const Vec3& p) {
    const DoomVertex v{to_int16(p.x, map_, "vertex x"), to_int16(p.y, map_, "vertex y")};
    const auto [it, added] = index_.try_emplace(key(v.x, v.y), vertices_.size());
    if (added) {
      if (vertices_.size() >= kMaxSegs) throw InputError("map " + map_.name + ": more than 65,535 vertices");
      vertices_.push_back(v);
      const double shift = std::hypot(p.x - v.x, p.y - v.y);
      ++stats_.split_vertices;
      stats_.max_shift = std::max(stats_.max_shift, shift);
      shift_sum_ += shift;
    }
    return static_cast<std::uint16_t>(it->second);
  }
  const DoomVertex& operator[](std::uint16_t i) const { return vertices_[i]; }

  std::vector<DoomVertex> finish() {
    stats_.mean_shift = stats_.split_vertices ? shift_sum_ / static_cast<double>(stats_.split_vertices) : 0.0;
    return std::move(vertices_);
  }

 private:
  const DoomMap& map_;
  RoundingStats& stats_;
  std::vector<DoomVertex> vertices_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  double shift_sum_ = 0;
};

using Bounds = std::array<std::int16_t, 4>;  // top, bottom, left, right

Bounds empty_bounds() {
  return {std::numeric_limits<std::int16_t>::min(), std::numeric_limits<std::int16_t>::max(),
          std::numeric_limits<std::int16_t>::max(), std::numeric_limits<std::int16_t>::min()};
}

void grow(Bounds& b, const DoomVertex& v) {
  b[0] = std::max(b[0], v.y);
  b[1] = std::min(b[1], v.y);
  b[2] = std::min(b[2], v.x);
  b[3] = std::max(b[3], v.x);
}

Bounds merged(const Bounds& a, const Bounds& c) {
  return {std::max(a[0], c[0]), std::min(a[1], c[1]), std::min(a[2], c[2]), std::max(a[3], c[3])};
}

class VanillaWriter {
 public:
  VanillaWriter(const Tree& tree, const DoomMap& map, const DoomSegs& segs, const IntegerLines& lines)
      : tree_(tree), map_(map), segs_(segs), lines_(lines), vertices_(map, out_.rounding) {
    for (std::uint32_t f = 0; f < tree.fragment_plane.size(); ++f) plane_owner_.try_emplace(tree.fragment_plane[f] >> 1, f);
  }

  VanillaBuild run() {
    if (!tree_.empty()) walk();
    out_.nodes.vertices = vertices_.finish();
    return std::move(out_);
  }

 private:
  // Post-order without recursion: a node is emitted after both its children, so the root is last.
  void walk() {
    struct Step {
      std::uint32_t node;
      bool expanded;
    };
    std::vector<Step> stack{{0, false}};
    while (!stack.empty()) {
      const Step s = stack.back();
      stack.pop_back();
      const Node& n = tree_.nodes[s.node];
      if (n.is_cell_leaf()) {
        emit_subsector(s.node);
      } else if (n.front == kNull || n.back == kNull) {
        throw std::logic_error("map " + map_.name + ": a leafy tree node with one child");
      } else if (!s.expanded) {
        stack.push_back({s.node, true});
        stack.push_back({n.back, false});
        stack.push_back({n.front, false});
      } else {
        emit_node(s.node);
      }
    }
  }

  void emit_subsector(std::uint32_t node) {
    const FragmentRange r = tree_.fragments_of(node);
    if (out_.nodes.subsectors.size() >= kMaxNodes) throw InputError("map " + map_.name + ": more than 32,767 subsectors");
    Bounds b = empty_bounds();
    const auto first = static_cast<std::uint16_t>(out_.nodes.segs.size());
    for (std::uint32_t f = r.begin; f < r.end; ++f) {
      const Seg s = make_seg(f);
      grow(b, vertices_[s.v1]);
      grow(b, vertices_[s.v2]);
      out_.nodes.segs.push_back(s);
    }
    done_.push_back({static_cast<std::uint16_t>(kSubsectorChild | out_.nodes.subsectors.size()), b});
    out_.nodes.subsectors.push_back({static_cast<std::uint16_t>(r.size()), first});
  }

  Seg make_seg(std::uint32_t f) {
    if (out_.nodes.segs.size() >= kMaxSegs) throw InputError("map " + map_.name + ": more than 65,535 segs");
    const std::uint32_t s = tree_.fragments[f].source;
    const auto pts = tree_.fragments.points(f);
    const auto [start, end] = side_ends(map_, segs_.linedef[s], segs_.side[s]);
    Seg seg;
    seg.v1 = vertices_.of(pts[0]);
    seg.v2 = vertices_.of(pts[1]);
    if (seg.v1 == seg.v2) ++out_.rounding.collapsed_segs;
    seg.angle = binary_angle(start, end);
    seg.linedef = segs_.linedef[s];
    seg.side = segs_.side[s];
    seg.offset = to_int16(std::hypot(pts[0].x - start.x, pts[0].y - start.y), map_, "seg offset");
    return seg;
  }

  void emit_node(std::uint32_t node) {
    if (out_.nodes.nodes.size() >= kMaxNodes) throw InputError("map " + map_.name + ": more than 32,767 nodes");
    const Done back = done_.back();
    done_.pop_back();
    const Done front = done_.back();
    done_.pop_back();
    const IntegerLine l = partition(tree_.nodes[node].plane);
    NodeRecord rec;
    rec.x = to_int16(l.x, map_, "partition x");
    rec.y = to_int16(l.y, map_, "partition y");
    rec.dx = to_int16(l.dx, map_, "partition dx");
    rec.dy = to_int16(l.dy, map_, "partition dy");
    rec.bbox = {front.bounds, back.bounds};
    rec.child = {front.child, back.child};
    done_.push_back({static_cast<std::uint16_t>(out_.nodes.nodes.size()), merged(front.bounds, back.bounds)});
    out_.nodes.nodes.push_back(rec);
  }

  // A segment's plane is its linedef's line; the stored direction puts the node's front on its right.
  IntegerLine partition(std::uint32_t plane) const {
    const auto owner = plane_owner_.find(plane >> 1);
    if (owner == plane_owner_.end()) {
      const auto free = lines_.find(tree_.planes[plane]);
      if (!free) throw std::logic_error("map " + map_.name + ": a partition plane that is neither a seg's nor snapped");
      return *free;
    }
    const std::uint32_t f = owner->second;
    const std::uint32_t s = tree_.fragments[f].source;
    auto [a, b] = side_ends(map_, segs_.linedef[s], segs_.side[s]);
    if (tree_.fragment_plane[f] != plane) std::swap(a, b);
    return {static_cast<std::int32_t>(a.x), static_cast<std::int32_t>(a.y), static_cast<std::int32_t>(b.x - a.x),
            static_cast<std::int32_t>(b.y - a.y)};
  }

  // A finished subtree: how its parent refers to it, and the box of its segs.
  struct Done {
    std::uint16_t child;
    Bounds bounds;
  };

  const Tree& tree_;
  const DoomMap& map_;
  const DoomSegs& segs_;
  const IntegerLines& lines_;
  VanillaBuild out_;
  VertexTable vertices_;
  std::unordered_map<std::uint32_t, std::uint32_t> plane_owner_;  // plane pair → a fragment in it
  std::vector<Done> done_;
};

}  // namespace

DoomSegs doom_segs(const DoomMap& map) {
  DoomSegs out;
  std::unordered_map<std::uint64_t, std::uint32_t> sector_along;  // by the side's two vertex keys
  const auto side_key = [](const Vec3& a, const Vec3& b) {
    return key(static_cast<std::int64_t>(a.x), static_cast<std::int64_t>(a.y)) * 0x9E3779B97F4A7C15ULL ^
           key(static_cast<std::int64_t>(b.x), static_cast<std::int64_t>(b.y));
  };
  for (std::size_t l = 0; l < map.linedefs.size(); ++l) {
    const Linedef& line = map.linedefs[l];
    if (line.v1 == line.v2 || (map.vertices[line.v1].x == map.vertices[line.v2].x &&
                               map.vertices[line.v1].y == map.vertices[line.v2].y)) {
      ++out.zero_length;
      continue;
    }
    for (std::uint8_t side = 0; side < 2; ++side) {
      if (line.sidenum[side] == kNoSidedef) continue;
      const auto [a, b] = side_ends(map, static_cast<std::uint16_t>(l), side);
      const std::uint32_t sector = map.sidedefs[line.sidenum[side]].sector;
      const auto [earlier, fresh] = sector_along.try_emplace(side_key(a, b), sector);
      if (!fresh && earlier->second != sector) {
        ++out.coincident_sides;
        continue;
      }
      const auto index = static_cast<std::uint32_t>(out.segs.size());
      out.segs.push_back(Polygon{{Vertex{a}, Vertex{b}}, index});
      out.sector.push_back(sector);
      out.linedef.push_back(static_cast<std::uint16_t>(l));
      out.side.push_back(side);
    }
  }
  return out;
}

Plane IntegerLines::snap(const Plane& p) {
  const Vec3 q = centre_ - p.n * p.distance(centre_);
  const std::int32_t x = static_cast<std::int32_t>(std::lround(q.x)), y = static_cast<std::int32_t>(std::lround(q.y));
  const std::int32_t dx = static_cast<std::int32_t>(std::lround(-p.n.y * kDirection));
  const std::int32_t dy = static_cast<std::int32_t>(std::lround(p.n.x * kDirection));
  const Vec3 a{static_cast<double>(x), static_cast<double>(y), 0}, b{static_cast<double>(x + dx), static_cast<double>(y + dy), 0};
  const Plane snapped = *line_through(a, b);
  std::lock_guard lock(mutex_);
  lines_.push_back({snapped, {x, y, dx, dy}});
  return snapped;
}

std::optional<IntegerLine> IntegerLines::find(const Plane& p) const {
  std::lock_guard lock(mutex_);
  for (const auto& [plane, line] : lines_) {
    if (plane == p) return line;
    if (plane.flipped() == p) return IntegerLine{line.x + line.dx, line.y + line.dy, -line.dx, -line.dy};
  }
  return std::nullopt;
}

VanillaBuild to_vanilla(const Tree& tree, const DoomMap& map, const DoomSegs& segs, const IntegerLines& lines) {
  return VanillaWriter(tree, map, segs, lines).run();
}

}  // namespace bsp
