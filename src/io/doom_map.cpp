#include "io/doom_map.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string_view>

#include "common/errors.h"

namespace bsp {

namespace {

// The lumps of a classic map in the order vanilla Doom's tools write them.
constexpr std::array<std::string_view, 10> kMapLumps = {"THINGS",   "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS",
                                                        "SSECTORS", "NODES",    "SECTORS",  "REJECT",   "BLOCKMAP"};
constexpr std::size_t kThingBytes = 10, kLinedefBytes = 14, kSidedefBytes = 30, kVertexBytes = 4, kSectorBytes = 26,
                      kSegBytes = 12, kSubsectorBytes = 4, kNodeBytes = 28;

using Bytes = std::vector<std::uint8_t>;

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

bool is_marker_name(const std::string& n) {
  const bool episode = n.size() == 4 && n[0] == 'E' && is_digit(n[1]) && n[2] == 'M' && is_digit(n[3]);
  const bool map = n.size() == 5 && n.starts_with("MAP") && is_digit(n[3]) && is_digit(n[4]);
  return episode || map;
}

bool is_marker(const Wad& wad, std::size_t i) {
  return is_marker_name(wad.lumps[i].name) && i + 1 < wad.lumps.size() && wad.lumps[i + 1].name == "THINGS";
}

std::optional<std::size_t> find_marker(const Wad& wad, const std::string& name) {
  for (std::size_t i = 0; i < wad.lumps.size(); ++i)
    if (wad.lumps[i].name == name && is_marker(wad, i)) return i;
  return std::nullopt;
}

std::optional<std::size_t> canonical_position(std::string_view name) {
  const auto it = std::find(kMapLumps.begin(), kMapLumps.end(), name);
  if (it == kMapLumps.end()) return std::nullopt;
  return static_cast<std::size_t>(it - kMapLumps.begin());
}

// One past the map's last lump: its lumps are the map-lump names that follow the marker.
std::size_t map_end(const Wad& wad, std::size_t marker) {
  std::size_t end = marker + 1;
  while (end < wad.lumps.size() && canonical_position(wad.lumps[end].name)) ++end;
  return end;
}

std::optional<std::size_t> find_map_lump(const Wad& wad, std::size_t marker, std::string_view name) {
  const std::size_t end = map_end(wad, marker);
  for (std::size_t i = marker + 1; i < end; ++i)
    if (wad.lumps[i].name == name) return i;
  return std::nullopt;
}

// Where messages about one map's lumps come from.
struct Origin {
  const std::string& file;
  const std::string& map;
  [[noreturn]] void fail(std::string_view lump, const std::string& problem) const {
    throw InputError(file + ": lump " + std::string(lump) + " of " + map + ": " + problem);
  }
};

const Bytes& lump_records(const Wad& wad, std::size_t marker, std::string_view name, std::size_t record_bytes,
                          const Origin& origin) {
  const auto index = find_map_lump(wad, marker, name);
  if (!index) throw InputError(origin.file + ": map " + origin.map + " has no " + std::string(name) + " lump");
  const Bytes& data = wad.lumps[*index].data;
  if (data.size() % record_bytes != 0)
    origin.fail(name, std::to_string(data.size()) + " bytes is not a multiple of " + std::to_string(record_bytes) +
                          "-byte records");
  return data;
}

std::uint16_t u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::int16_t s16(const std::uint8_t* p) { return static_cast<std::int16_t>(u16(p)); }

std::string name8(const std::uint8_t* p) {
  const std::string s(reinterpret_cast<const char*>(p), 8);
  return s.substr(0, s.find('\0'));
}

template <class T, class Decode>
std::vector<T> decode(const Bytes& data, std::size_t record_bytes, Decode one) {
  std::vector<T> out;
  out.reserve(data.size() / record_bytes);
  for (std::size_t at = 0; at < data.size(); at += record_bytes) out.push_back(one(data.data() + at));
  return out;
}

std::vector<DoomVertex> decode_vertices(const Bytes& data) {
  return decode<DoomVertex>(data, kVertexBytes, [](const std::uint8_t* p) { return DoomVertex{s16(p), s16(p + 2)}; });
}

std::vector<Linedef> decode_linedefs(const Bytes& data) {
  return decode<Linedef>(data, kLinedefBytes, [](const std::uint8_t* p) {
    return Linedef{u16(p), u16(p + 2), u16(p + 4), u16(p + 6), u16(p + 8), {u16(p + 10), u16(p + 12)}};
  });
}

std::vector<Sidedef> decode_sidedefs(const Bytes& data) {
  return decode<Sidedef>(data, kSidedefBytes, [](const std::uint8_t* p) {
    return Sidedef{s16(p), s16(p + 2), name8(p + 4), name8(p + 12), name8(p + 20), u16(p + 28)};
  });
}

std::vector<Sector> decode_sectors(const Bytes& data) {
  return decode<Sector>(data, kSectorBytes, [](const std::uint8_t* p) {
    return Sector{s16(p), s16(p + 2), name8(p + 4), name8(p + 12), s16(p + 20), s16(p + 22), s16(p + 24)};
  });
}

std::vector<Seg> decode_segs(const Bytes& data) {
  return decode<Seg>(data, kSegBytes, [](const std::uint8_t* p) {
    return Seg{u16(p), u16(p + 2), u16(p + 4), u16(p + 6), u16(p + 8), s16(p + 10)};
  });
}

std::vector<Subsector> decode_subsectors(const Bytes& data) {
  return decode<Subsector>(data, kSubsectorBytes, [](const std::uint8_t* p) { return Subsector{u16(p), u16(p + 2)}; });
}

std::vector<NodeRecord> decode_nodes(const Bytes& data) {
  return decode<NodeRecord>(data, kNodeBytes, [](const std::uint8_t* p) {
    NodeRecord n{s16(p), s16(p + 2), s16(p + 4), s16(p + 6), {}, {u16(p + 24), u16(p + 26)}};
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 4; ++k) n.bbox[c][k] = s16(p + 8 + 8 * c + 2 * k);
    return n;
  });
}

// "what N uses KIND I of COUNT" unless I < COUNT.
void check_index(const Origin& origin, std::string_view lump, const std::string& what, std::size_t i,
                 const std::string& kind, std::size_t index, std::size_t count) {
  if (index >= count)
    origin.fail(lump, what + " " + std::to_string(i) + " uses " + kind + " " + std::to_string(index) + " of " +
                          std::to_string(count));
}

void check_linedefs(const std::vector<Linedef>& linedefs, std::size_t vertices, std::size_t sidedefs,
                    const Origin& origin) {
  for (std::size_t i = 0; i < linedefs.size(); ++i) {
    const Linedef& l = linedefs[i];
    check_index(origin, "LINEDEFS", "linedef", i, "vertex", l.v1, vertices);
    check_index(origin, "LINEDEFS", "linedef", i, "vertex", l.v2, vertices);
    for (const std::uint16_t side : l.sidenum)
      if (side != kNoSidedef) check_index(origin, "LINEDEFS", "linedef", i, "sidedef", side, sidedefs);
  }
}

std::size_t vertices_used(const std::vector<Linedef>& linedefs) {
  std::size_t n = 0;
  for (const Linedef& l : linedefs) n = std::max<std::size_t>({n, l.v1 + 1u, l.v2 + 1u});
  return n;
}

void check_segs(const VanillaNodes& n, std::size_t linedefs, const Origin& origin) {
  for (std::size_t i = 0; i < n.segs.size(); ++i) {
    check_index(origin, "SEGS", "seg", i, "vertex", n.segs[i].v1, n.vertices.size());
    check_index(origin, "SEGS", "seg", i, "vertex", n.segs[i].v2, n.vertices.size());
    check_index(origin, "SEGS", "seg", i, "linedef", n.segs[i].linedef, linedefs);
  }
}

void check_subsectors(const VanillaNodes& n, const Origin& origin) {
  for (std::size_t i = 0; i < n.subsectors.size(); ++i) {
    const Subsector& s = n.subsectors[i];
    if (std::size_t{s.first} + s.count > n.segs.size())
      origin.fail("SSECTORS", "subsector " + std::to_string(i) + " runs past the last seg: first " +
                                  std::to_string(s.first) + ", count " + std::to_string(s.count) + ", of " +
                                  std::to_string(n.segs.size()) + " segs");
  }
}

void check_children(const VanillaNodes& n, const Origin& origin) {
  for (std::size_t i = 0; i < n.nodes.size(); ++i)
    for (const std::uint16_t child : n.nodes[i].child) {
      const bool leaf = (child & kSubsectorChild) != 0;
      const std::size_t index = child & ~kSubsectorChild;
      check_index(origin, "NODES", "node", i, leaf ? "subsector" : "node", index,
                  leaf ? n.subsectors.size() : n.nodes.size());
    }
}

void reject_extended_nodes(const Bytes& nodes, const Origin& origin) {
  const std::string signature(nodes.begin(),
                              nodes.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(4, nodes.size())));
  if (signature == "XNOD" || signature == "ZNOD")
    origin.fail("NODES", "ZDBSP extended nodes (" + signature + ") are not supported, only vanilla nodes");
}

void put16(Bytes& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xff));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

Bytes encode_vertices(const std::vector<DoomVertex>& vertices) {
  Bytes out;
  for (const DoomVertex& v : vertices) {
    put16(out, static_cast<std::uint16_t>(v.x));
    put16(out, static_cast<std::uint16_t>(v.y));
  }
  return out;
}

Bytes encode_segs(const std::vector<Seg>& segs) {
  Bytes out;
  for (const Seg& s : segs)
    for (const std::uint16_t v : {s.v1, s.v2, s.angle, s.linedef, s.side, static_cast<std::uint16_t>(s.offset)})
      put16(out, v);
  return out;
}

Bytes encode_subsectors(const std::vector<Subsector>& subsectors) {
  Bytes out;
  for (const Subsector& s : subsectors) {
    put16(out, s.count);
    put16(out, s.first);
  }
  return out;
}

Bytes encode_nodes(const std::vector<NodeRecord>& nodes) {
  Bytes out;
  for (const NodeRecord& n : nodes) {
    for (const std::int16_t v : {n.x, n.y, n.dx, n.dy}) put16(out, static_cast<std::uint16_t>(v));
    for (const auto& box : n.bbox)
      for (const std::int16_t v : box) put16(out, static_cast<std::uint16_t>(v));
    put16(out, n.child[0]);
    put16(out, n.child[1]);
  }
  return out;
}

// Replaces the map's lump `name`, or inserts it before the first map lump that vanilla order puts after it.
void put_map_lump(Wad& wad, std::size_t marker, std::string_view name, Bytes data) {
  if (const auto index = find_map_lump(wad, marker, name)) {
    wad.lumps[*index].data = std::move(data);
    return;
  }
  const std::size_t end = map_end(wad, marker);
  std::size_t at = marker + 1;
  while (at < end && *canonical_position(wad.lumps[at].name) < *canonical_position(name)) ++at;
  wad.lumps.insert(wad.lumps.begin() + static_cast<std::ptrdiff_t>(at), Lump{std::string(name), std::move(data)});
}

}  // namespace

std::vector<std::string> map_names(const Wad& wad) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < wad.lumps.size(); ++i)
    if (is_marker(wad, i)) names.push_back(wad.lumps[i].name);
  return names;
}

DoomMap read_map(const Wad& wad, const std::string& name, const std::string& file) {
  const auto found = find_marker(wad, name);
  if (!found) throw InputError(file + ": no map " + name);
  const std::size_t marker = *found;
  const Origin origin{file, name};
  DoomMap map{name,
              marker,
              decode_vertices(lump_records(wad, marker, "VERTEXES", kVertexBytes, origin)),
              decode_linedefs(lump_records(wad, marker, "LINEDEFS", kLinedefBytes, origin)),
              decode_sidedefs(lump_records(wad, marker, "SIDEDEFS", kSidedefBytes, origin)),
              decode_sectors(lump_records(wad, marker, "SECTORS", kSectorBytes, origin)),
              decode<DoomVertex>(lump_records(wad, marker, "THINGS", kThingBytes, origin), kThingBytes,
                                 [](const std::uint8_t* p) { return DoomVertex{s16(p), s16(p + 2)}; })};
  check_linedefs(map.linedefs, map.vertices.size(), map.sidedefs.size(), origin);
  for (std::size_t i = 0; i < map.sidedefs.size(); ++i)
    check_index(origin, "SIDEDEFS", "sidedef", i, "sector", map.sidedefs[i].sector, map.sectors.size());
  map.vertices.resize(vertices_used(map.linedefs));
  return map;
}

VanillaNodes read_vanilla_nodes(const Wad& wad, const DoomMap& map, const std::string& file) {
  const Origin origin{file, map.name};
  if (const auto nodes = find_map_lump(wad, map.marker, "NODES")) reject_extended_nodes(wad.lumps[*nodes].data, origin);
  VanillaNodes n{decode_vertices(lump_records(wad, map.marker, "VERTEXES", kVertexBytes, origin)),
                 decode_segs(lump_records(wad, map.marker, "SEGS", kSegBytes, origin)),
                 decode_subsectors(lump_records(wad, map.marker, "SSECTORS", kSubsectorBytes, origin)),
                 decode_nodes(lump_records(wad, map.marker, "NODES", kNodeBytes, origin))};
  check_segs(n, map.linedefs.size(), origin);
  check_subsectors(n, origin);
  check_children(n, origin);
  return n;
}

void replace_nodes(Wad& wad, const DoomMap& map, const VanillaNodes& nodes) {
  put_map_lump(wad, map.marker, "VERTEXES", encode_vertices(nodes.vertices));
  put_map_lump(wad, map.marker, "SEGS", encode_segs(nodes.segs));
  put_map_lump(wad, map.marker, "SSECTORS", encode_subsectors(nodes.subsectors));
  put_map_lump(wad, map.marker, "NODES", encode_nodes(nodes.nodes));
}

Wad single_map_pwad(const Wad& wad, const DoomMap& map) {
  const auto first = wad.lumps.begin() + static_cast<std::ptrdiff_t>(map.marker);
  return Wad{false,
             std::vector<Lump>(first, wad.lumps.begin() + static_cast<std::ptrdiff_t>(map_end(wad, map.marker)))};
}

}  // namespace bsp
