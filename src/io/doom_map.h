#pragma once
// Classic Doom maps and their vanilla BSP [DoomSpecs]. A map is a
// marker lump (ExMy or MAPxx) followed by its lumps: THINGS, LINEDEFS, SIDEDEFS, VERTEXES, SEGS,
// SSECTORS, NODES, SECTORS, REJECT, BLOCKMAP. The node builder's output is SEGS (pieces of
// linedef sides), SSECTORS (convex leaves, each a run of consecutive segs), NODES (partition lines)
// and the split vertices it appends to VERTEXES after the map's own.
//
// How the vanilla renderer reads a node (R_PointOnSide in r_main.c of the Doom source): child[0]
// is the right (front) side of the partition from (x, y) along (dx, dy), child[1] the left (back)
// side. In the general case a point on the partition line goes to the back; the shortcuts for
// vertical and horizontal partitions and for differing sign bits put some on-line points on the
// front, so a correct tree must keep on-line geometry valid on either side.
//
// Every reader throws InputError with one line "FILE: lump LUMP of MAP: problem" (or "FILE: map
// MAP has no LUMP lump", "FILE: no map MAP").
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/wad.h"

namespace bsp {

constexpr std::uint16_t kNoSidedef = 0xFFFF;       // a linedef's missing side
constexpr std::uint16_t kSubsectorChild = 0x8000;  // a node child that is a subsector (index in the low bits)

struct DoomVertex {
  std::int16_t x = 0, y = 0;
};

struct Linedef {
  std::uint16_t v1 = 0, v2 = 0, flags = 0, special = 0, tag = 0;
  std::array<std::uint16_t, 2> sidenum{kNoSidedef, kNoSidedef};  // right (front), left (back)
};

struct Sidedef {
  std::int16_t x_offset = 0, y_offset = 0;
  std::string upper, lower, middle;  // texture names, NUL padding removed
  std::uint16_t sector = 0;
};

struct Sector {
  std::int16_t floor_height = 0, ceiling_height = 0;
  std::string floor_texture, ceiling_texture;
  std::int16_t light = 0, special = 0, tag = 0;
};

struct DoomMap {
  std::string name;
  std::size_t marker = 0;  // index of the marker lump in the Wad
  // VERTEXES up to the last vertex a linedef uses: node builders append their split vertices after
  // the map's own, so what follows belongs to the nodes (VanillaNodes::vertices has them all).
  std::vector<DoomVertex> vertices;
  std::vector<Linedef> linedefs;
  std::vector<Sidedef> sidedefs;
  std::vector<Sector> sectors;
  std::vector<DoomVertex> things;  // where the map's things stand (THINGS' x and y)
};

struct Seg {
  std::uint16_t v1 = 0, v2 = 0;
  std::uint16_t angle = 0;  // binary angle measurement: 0x10000 is a full turn, 0 is east
  std::uint16_t linedef = 0;
  std::uint16_t side = 0;   // 0: the linedef's right side, running with it; 1: its left side, against it
  std::int16_t offset = 0;  // from the start of its side (linedef v1 for side 0, v2 for side 1) to the seg's v1
};

struct Subsector {
  std::uint16_t count = 0, first = 0;  // segs [first, first + count)
};

struct NodeRecord {
  std::int16_t x = 0, y = 0, dx = 0, dy = 0;          // the partition line
  std::array<std::array<std::int16_t, 4>, 2> bbox{};  // per child: top, bottom, left, right
  std::array<std::uint16_t, 2> child{};               // right (front), left (back); kSubsectorChild marks a subsector
};

// The root is the last node; a map with a single subsector has no nodes (that subsector is the tree).
struct VanillaNodes {
  std::vector<DoomVertex> vertices;  // all of VERTEXES, the map's own first
  std::vector<Seg> segs;
  std::vector<Subsector> subsectors;
  std::vector<NodeRecord> nodes;
};

// The maps in lump order: markers ExMy or MAPxx followed by a THINGS lump.
std::vector<std::string> map_names(const Wad& wad);

// Decodes the map's THINGS (sizes only), LINEDEFS, SIDEDEFS, VERTEXES and SECTORS and checks every
// index: linedef vertices and sidedefs, sidedef sectors.
DoomMap read_map(const Wad& wad, const std::string& name, const std::string& file_for_errors);

// Decodes SEGS, SSECTORS, NODES and VERTEXES and checks their indices: seg vertices and linedefs,
// subsector seg ranges, node children. ZDBSP's extended or compressed nodes (XNOD, ZNOD) are
// rejected by name.
VanillaNodes read_vanilla_nodes(const Wad& wad, const DoomMap& map, const std::string& file_for_errors);

// Writes NODES, SEGS, SSECTORS and VERTEXES in the vanilla layouts. Other lumps keep their bytes and
// places; a node lump the map lacks is inserted where the vanilla order puts it, which shifts the
// lumps after it (re-read the markers of later maps).
void replace_nodes(Wad& wad, const DoomMap& map, const VanillaNodes& nodes);

// A PWAD holding only the map's marker and lumps, the input an external node builder needs.
Wad single_map_pwad(const Wad& wad, const DoomMap& map);

}  // namespace bsp
