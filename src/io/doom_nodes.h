#pragma once
// Doom maps as 2D scenes, and leafy trees as vanilla nodes ([DoomSpecs]; formats in io/doom_map.h).
//
// Map to scene: every linedef side is one segment (but a side coinciding with another, DoomSegs) (geometry/segment2.h), v1 → v2 for the right
// side and v2 → v1 for the left, so a segment's front (its right) faces the sector of its side, the
// segment's leaf group (tree/build.h): a leafy tree's leaves are then Doom's subsectors, convex and
// of one sector.
//
// Tree to nodes: nodes in post-order (the root last, as the engine expects), subsectors in the same
// walk, each one's segs consecutive. A partition line is stored as (x, y, dx, dy) in integers: a
// segment's plane by its linedef's two vertices, directed so the node's front is on the line's
// right; a free plane by the two integer points IntegerLines snapped it through. Split vertices are
// rounded to the nearest integer point (halves away from zero) and shared by every seg that ends
// there; a seg's angle is its linedef's (plus a half turn for the left side) and its offset the
// rounded exact distance from the start of its side along the linedef, as the engine draws textures
// from them. What rounding does is measured (VanillaBuild::rounding).
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "geometry/polygon.h"
#include "io/doom_map.h"
#include "tree/tree.h"

namespace bsp {

struct DoomSegs {
  std::vector<Polygon> segs;           // 2D segments; Polygon::source is the index here
  std::vector<std::uint32_t> sector;   // per seg: the sector its side faces
  std::vector<std::uint16_t> linedef;  // per seg
  std::vector<std::uint8_t> side;      // per seg: 0 right, 1 left
  std::uint64_t zero_length = 0;       // linedefs whose vertices coincide: no segment
  // Sides that run exactly along an earlier side, the same way, facing another sector (overlapping
  // linedefs, a map error): no plane parts the two, so no subsector could hold them with one sector.
  // The later one is left out.
  std::uint64_t coincident_sides = 0;
};

DoomSegs doom_segs(const DoomMap& map);

// A partition line through two integer points, stored as a vanilla node stores it.
struct IntegerLine {
  std::int32_t x = 0, y = 0, dx = 0, dy = 0;
};

// Free planes snapped to lines Doom can store: through the integer point nearest the plane's point
// closest to the map's centre, along the nearest integer direction of length at least kDirection.
// Remembers each snapped plane's integer line, so the nodes store exactly the line the tree was
// built with. Thread-safe: a build's tasks may snap at once.
class IntegerLines {
 public:
  // Integer directions are at least this long, so rounding turns them by at most about 1/kDirection rad.
  static constexpr double kDirection = 1024;

  explicit IntegerLines(const Vec3& centre) : centre_(centre) {}
  Plane snap(const Plane& p);
  // The integer line of a plane snap() returned, directed so the plane's front is on its right.
  std::optional<IntegerLine> find(const Plane& p) const;

 private:
  Vec3 centre_;
  mutable std::mutex mutex_;
  std::vector<std::pair<Plane, IntegerLine>> lines_;
};

// What rounding split vertices to integers did.
struct RoundingStats {
  std::uint64_t split_vertices = 0;  // distinct vertices made by splits
  double max_shift = 0;              // largest distance from an exact split point to its rounded one
  double mean_shift = 0;
  std::uint64_t collapsed_segs = 0;  // segs whose two ends round to one point
};

struct VanillaBuild {
  VanillaNodes nodes;
  RoundingStats rounding;
};

// The vanilla lumps of a leafy tree built from doom_segs(map). Throws InputError naming the map
// when a limit of the format is exceeded (32,767 nodes or subsectors, 65,535 segs or vertices, a
// coordinate outside 16 bits).
VanillaBuild to_vanilla(const Tree& tree, const DoomMap& map, const DoomSegs& segs, const IntegerLines& lines);

}  // namespace bsp
