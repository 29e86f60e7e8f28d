// Doom's WAD files, classic maps and vanilla nodes [DoomSpecs]:
// Freedoom's WADs read and written again with every lump byte for byte, every malformed header,
// directory and map lump rejected with one line naming the file, the lump and the problem, the
// tree statistics of a small hand-made tree, and the structural check of vanilla nodes passing on
// ZDBSP's output for a Freedoom map while catching each corruption of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include "cli_runner.h"
#include "common/errors.h"
#include "io/doom_map.h"
#include "io/doom_tree_stats.h"
#include "io/wad.h"
#include "validate/doom_check.h"

using namespace bsp;
namespace fs = std::filesystem;

namespace {

const std::string kFreedoom1 = "/usr/share/games/doom/freedoom1.wad";
const std::string kFreedoom2 = "/usr/share/games/doom/freedoom2.wad";

#define SKIP_WITHOUT(path) \
  if (!fs::exists(path)) GTEST_SKIP() << path << " is not installed (apt-get install freedoom)"

std::string le32(std::int32_t v) {
  std::string s(4, '\0');
  for (int b = 0; b < 4; ++b) s[b] = static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * b)) & 0xff);
  return s;
}

std::string entry(std::int32_t offset, std::int32_t size, const std::string& name) {
  return le32(offset) + le32(size) + name + std::string(8 - name.size(), '\0');
}

// A PWAD of one 4-byte lump "DATA" at offset 12 with its directory after it, `patch` applied to the bytes.
std::string small_wad(const std::function<void(std::string&)>& patch = {}) {
  std::string bytes = "PWAD" + le32(1) + le32(16) + "abcd" + entry(12, 4, "DATA");
  if (patch) patch(bytes);
  return bytes;
}

// `f` throws InputError whose message is one line containing every one of `parts`.
void expect_input_error(const std::function<void()>& f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  }
}

std::size_t lump_index(const Wad& wad, const DoomMap& map, const std::string& name) {
  for (std::size_t i = map.marker + 1; i < wad.lumps.size(); ++i)
    if (wad.lumps[i].name == name) return i;
  ADD_FAILURE() << "no lump " << name;
  return 0;
}

void put16(std::vector<std::uint8_t>& data, std::size_t at, std::uint16_t v) {
  data[at] = static_cast<std::uint8_t>(v & 0xff);
  data[at + 1] = static_cast<std::uint8_t>(v >> 8);
}

// Freedoom 2's MAP01 alone, as a PWAD.
Wad map01_pwad() {
  const Wad wad = read_wad(kFreedoom2);
  return single_map_pwad(wad, read_map(wad, "MAP01", kFreedoom2));
}

}  // namespace

// ---- WAD files ----

TEST(WadRoundTrip, FreedoomLumpsComeBackByteForByte) {
  SKIP_WITHOUT(kFreedoom2);
  const Wad original = read_wad(kFreedoom2);
  const fs::path dir = bsp::testing::fresh_test_dir("bspbench_wad");
  write_wad((dir / "copy.wad").string(), original);
  const Wad copy = read_wad((dir / "copy.wad").string());
  fs::remove_all(dir);
  EXPECT_TRUE(copy.iwad);
  ASSERT_EQ(copy.lumps.size(), original.lumps.size());
  for (std::size_t i = 0; i < copy.lumps.size(); ++i) {
    EXPECT_EQ(copy.lumps[i].name, original.lumps[i].name) << "lump " << i;
    EXPECT_TRUE(copy.lumps[i].data == original.lumps[i].data) << "lump " << i << " " << original.lumps[i].name;
  }
}

TEST(WadRoundTrip, WritingAReadWadIsAFixedPoint) {
  const std::string once = wad_bytes(parse_wad(small_wad(), "small.wad"));
  EXPECT_EQ(wad_bytes(parse_wad(once, "once.wad")), once);
  const Wad w = parse_wad(once, "once.wad");
  ASSERT_EQ(w.lumps.size(), 1u);
  EXPECT_FALSE(w.iwad);
  EXPECT_EQ(w.lumps[0].name, "DATA");
  EXPECT_EQ(std::string(w.lumps[0].data.begin(), w.lumps[0].data.end()), "abcd");
}

TEST(WadRoundTrip, EightCharacterNamesAndEmptyLumps) {
  const Wad w{false, {{"FULLNAME", {1, 2, 3}}, {"MARKER", {}}, {"X", {9}}}};
  const Wad back = parse_wad(wad_bytes(w), "names.wad");
  ASSERT_EQ(back.lumps.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.lumps[i].name, w.lumps[i].name);
    EXPECT_EQ(back.lumps[i].data, w.lumps[i].data);
  }
  EXPECT_THROW(wad_bytes(Wad{false, {{"NINECHARS", {}}}}), std::invalid_argument);
}

TEST(WadMalformed, FileShorterThanTheHeader) {
  expect_input_error([] { parse_wad("PWAD\1\0", "short.wad"); },
                     {"short.wad: ", "shorter than the 12-byte WAD header"});
}

TEST(WadMalformed, BadMagic) {
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b[0] = 'X'; }), "magic.wad"); },
                     {"magic.wad: ", "not a WAD"});
}

TEST(WadMalformed, DirectoryPastTheEnd) {
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(4, 4, le32(2)); }), "dir.wad"); },
                     {"dir.wad: ", "directory of 2 entries", "past the end"});
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(8, 4, le32(1000)); }), "dir.wad"); },
                     {"dir.wad: ", "at offset 1000", "past the end"});
}

TEST(WadMalformed, LumpPastTheEnd) {
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(20, 4, le32(30)); }), "lump.wad"); },
                     {"lump.wad: ", "directory entry 0 (lump DATA)", "30 bytes at offset 12", "past the end"});
}

TEST(WadMalformed, NegativeCountSizeAndOffset) {
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(4, 4, le32(-1)); }), "neg.wad"); },
                     {"neg.wad: header: negative lump count -1"});
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(8, 4, le32(-16)); }), "neg.wad"); },
                     {"neg.wad: header: negative directory offset -16"});
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(20, 4, le32(-4)); }), "neg.wad"); },
                     {"neg.wad: directory entry 0 (lump DATA): negative size -4"});
  expect_input_error([] { parse_wad(small_wad([](std::string& b) { b.replace(16, 4, le32(-12)); }), "neg.wad"); },
                     {"neg.wad: directory entry 0 (lump DATA): negative offset -12"});
}

TEST(WadMalformed, MissingFile) {
  expect_input_error([] { read_wad("/nonexistent/x.wad"); }, {"/nonexistent/x.wad: cannot open"});
}

// ---- maps ----

TEST(DoomMap, FreedoomMapNames) {
  SKIP_WITHOUT(kFreedoom1);
  SKIP_WITHOUT(kFreedoom2);
  const std::vector<std::string> doom1 = map_names(read_wad(kFreedoom1));
  const std::vector<std::string> doom2 = map_names(read_wad(kFreedoom2));
  ASSERT_EQ(doom1.size(), 36u);
  EXPECT_EQ(doom1.front(), "E1M1");
  EXPECT_EQ(doom1.back(), "E4M9");
  ASSERT_EQ(doom2.size(), 32u);
  EXPECT_EQ(doom2.front(), "MAP01");
  EXPECT_EQ(doom2.back(), "MAP32");
}

TEST(DoomMap, EveryFreedoomMapAndItsShippedNodesRead) {
  SKIP_WITHOUT(kFreedoom1);
  SKIP_WITHOUT(kFreedoom2);
  for (const std::string& file : {kFreedoom1, kFreedoom2}) {
    const Wad wad = read_wad(file);
    for (const std::string& name : map_names(wad)) {
      SCOPED_TRACE(file + " " + name);
      const DoomMap map = read_map(wad, name, file);
      const VanillaNodes nodes = read_vanilla_nodes(wad, map, file);
      EXPECT_FALSE(map.linedefs.empty());
      EXPECT_FALSE(nodes.nodes.empty());
      ASSERT_LE(map.vertices.size(), nodes.vertices.size());
      EXPECT_TRUE(std::equal(map.vertices.begin(), map.vertices.end(), nodes.vertices.begin(),
                             [](DoomVertex a, DoomVertex b) { return a.x == b.x && a.y == b.y; }));
    }
  }
}

TEST(DoomMap, DecodesRecordFields) {
  // One square room: 4 vertices, 4 one-sided linedefs, 1 sidedef, 1 sector.
  std::vector<std::uint8_t> vertexes, linedefs, sidedefs(30), sectors(26);
  const int xy[4][2] = {{0, 0}, {0, 64}, {-64, 64}, {-64, 0}};
  for (const auto& p : xy)
    for (const int c : p)
      vertexes.insert(vertexes.end(),
                      {static_cast<std::uint8_t>(c & 0xff), static_cast<std::uint8_t>((c >> 8) & 0xff)});
  for (std::uint16_t i = 0; i < 4; ++i)
    for (const std::uint16_t v : {i, static_cast<std::uint16_t>((i + 1) % 4), std::uint16_t{1}, std::uint16_t{0},
                                  std::uint16_t{0}, std::uint16_t{0}, kNoSidedef})
      linedefs.insert(linedefs.end(), {static_cast<std::uint8_t>(v & 0xff), static_cast<std::uint8_t>(v >> 8)});
  put16(sidedefs, 0, static_cast<std::uint16_t>(-8));
  std::copy_n("STARTAN3", 8, sidedefs.begin() + 20);
  put16(sectors, 2, 128);
  std::copy_n("FLAT1\0\0\0", 8, sectors.begin() + 4);
  put16(sectors, 20, 160);
  const Wad wad{false,
                {{"MAP07", {}},
                 {"THINGS", {}},
                 {"LINEDEFS", linedefs},
                 {"SIDEDEFS", sidedefs},
                 {"VERTEXES", vertexes},
                 {"SECTORS", sectors}}};
  const DoomMap map = read_map(wad, "MAP07", "room.wad");
  EXPECT_EQ(map.marker, 0u);
  ASSERT_EQ(map.vertices.size(), 4u);
  EXPECT_EQ(map.vertices[2].x, -64);
  EXPECT_EQ(map.vertices[2].y, 64);
  ASSERT_EQ(map.linedefs.size(), 4u);
  EXPECT_EQ(map.linedefs[3].v2, 0);
  EXPECT_EQ(map.linedefs[3].flags, 1);
  EXPECT_EQ(map.linedefs[3].sidenum[1], kNoSidedef);
  EXPECT_EQ(map.sidedefs[0].x_offset, -8);
  EXPECT_EQ(map.sidedefs[0].middle, "STARTAN3");
  EXPECT_EQ(map.sidedefs[0].upper, "");
  EXPECT_EQ(map.sectors[0].ceiling_height, 128);
  EXPECT_EQ(map.sectors[0].floor_texture, "FLAT1");
  EXPECT_EQ(map.sectors[0].light, 160);
  expect_input_error([&] { read_vanilla_nodes(wad, map, "room.wad"); }, {"room.wad: map MAP07 has no SEGS lump"});
}

TEST(DoomMap, MissingMapAndMissingLump) {
  SKIP_WITHOUT(kFreedoom2);
  Wad pwad = map01_pwad();
  expect_input_error([&] { read_map(pwad, "MAP02", "one.wad"); }, {"one.wad: no map MAP02"});
  pwad.lumps.erase(pwad.lumps.begin() +
                   static_cast<std::ptrdiff_t>(lump_index(pwad, read_map(pwad, "MAP01", "one.wad"), "SECTORS")));
  expect_input_error([&] { read_map(pwad, "MAP01", "one.wad"); }, {"one.wad: map MAP01 has no SECTORS lump"});
}

TEST(DoomMap, TruncatedLumpsAreNamed) {
  SKIP_WITHOUT(kFreedoom2);
  for (const std::string lump :
       {"THINGS", "LINEDEFS", "SIDEDEFS", "VERTEXES", "SECTORS", "SEGS", "SSECTORS", "NODES"}) {
    Wad pwad = map01_pwad();
    const DoomMap map = read_map(pwad, "MAP01", "one.wad");
    pwad.lumps[lump_index(pwad, map, lump)].data.pop_back();
    expect_input_error([&] { read_vanilla_nodes(pwad, read_map(pwad, "MAP01", "one.wad"), "one.wad"); },
                       {"one.wad: lump " + lump + " of MAP01: ", "bytes is not a multiple of", "-byte records"});
  }
}

TEST(DoomMap, OutOfRangeMapIndicesAreNamed) {
  SKIP_WITHOUT(kFreedoom2);
  const Wad pristine = map01_pwad();
  const DoomMap map = read_map(pristine, "MAP01", "one.wad");
  const std::size_t vertexes = pristine.lumps[lump_index(pristine, map, "VERTEXES")].data.size() / 4;
  struct Case {
    std::string lump;
    std::size_t at;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"LINEDEFS", 14 * 12 + 2, "lump LINEDEFS of MAP01: linedef 12 uses vertex 65000 of " + std::to_string(vertexes)},
      {"LINEDEFS", 14 * 5 + 10,
       "lump LINEDEFS of MAP01: linedef 5 uses sidedef 65000 of " + std::to_string(map.sidedefs.size())},
      {"SIDEDEFS", 30 * 7 + 28,
       "lump SIDEDEFS of MAP01: sidedef 7 uses sector 65000 of " + std::to_string(map.sectors.size())}};
  for (const Case& c : cases) {
    Wad pwad = pristine;
    put16(pwad.lumps[lump_index(pwad, map, c.lump)].data, c.at, 65000);
    expect_input_error([&] { read_map(pwad, "MAP01", "one.wad"); }, {"one.wad: " + c.message});
  }
}

TEST(DoomMap, OutOfRangeNodeIndicesAreNamed) {
  SKIP_WITHOUT(kFreedoom2);
  const Wad pristine = map01_pwad();
  const DoomMap map = read_map(pristine, "MAP01", "one.wad");
  const VanillaNodes nodes = read_vanilla_nodes(pristine, map, "one.wad");
  struct Case {
    std::string lump;
    std::size_t at;
    std::uint16_t value;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"SEGS", 12 * 3 + 2, 65000,
       "lump SEGS of MAP01: seg 3 uses vertex 65000 of " + std::to_string(nodes.vertices.size())},
      {"SEGS", 12 * 4 + 6, 65000,
       "lump SEGS of MAP01: seg 4 uses linedef 65000 of " + std::to_string(map.linedefs.size())},
      {"SSECTORS", 4 * (nodes.subsectors.size() - 1) + 2, static_cast<std::uint16_t>(nodes.segs.size()),
       "lump SSECTORS of MAP01: subsector " + std::to_string(nodes.subsectors.size() - 1) + " runs past the last seg"},
      {"NODES", 28 * 2 + 24, 0x7000,
       "lump NODES of MAP01: node 2 uses node 28672 of " + std::to_string(nodes.nodes.size())},
      {"NODES", 28 * 2 + 26, 0xF000,
       "lump NODES of MAP01: node 2 uses subsector 28672 of " + std::to_string(nodes.subsectors.size())}};
  for (const Case& c : cases) {
    Wad pwad = pristine;
    put16(pwad.lumps[lump_index(pwad, map, c.lump)].data, c.at, c.value);
    expect_input_error([&] { read_vanilla_nodes(pwad, map, "one.wad"); }, {"one.wad: " + c.message});
  }
}

TEST(DoomMap, ExtendedNodesAreRejectedByName) {
  SKIP_WITHOUT(kFreedoom2);
  Wad pwad = map01_pwad();
  const DoomMap map = read_map(pwad, "MAP01", "one.wad");
  pwad.lumps[lump_index(pwad, map, "NODES")].data = {'X', 'N', 'O', 'D', 0, 0, 0, 0};
  expect_input_error([&] { read_vanilla_nodes(pwad, map, "one.wad"); },
                     {"one.wad: lump NODES of MAP01: ZDBSP extended nodes (XNOD) are not supported"});
}

TEST(DoomMap, ReplacingNodesKeepsEveryOtherLumpByteForByte) {
  SKIP_WITHOUT(kFreedoom2);
  const Wad original = read_wad(kFreedoom2);
  const DoomMap map = read_map(original, "MAP05", kFreedoom2);
  VanillaNodes nodes = read_vanilla_nodes(original, map, kFreedoom2);
  Wad same = original;
  replace_nodes(same, map, nodes);
  ASSERT_EQ(same.lumps.size(), original.lumps.size());
  for (std::size_t i = 0; i < same.lumps.size(); ++i)
    EXPECT_TRUE(same.lumps[i].data == original.lumps[i].data)
        << "re-encoding changed lump " << i << " " << original.lumps[i].name;

  nodes.nodes.back().bbox[1][3] = 12345;
  nodes.vertices.push_back({-7, 9});
  Wad changed = original;
  replace_nodes(changed, map, nodes);
  ASSERT_EQ(changed.lumps.size(), original.lumps.size());
  for (std::size_t i = 0; i < changed.lumps.size(); ++i) {
    EXPECT_EQ(changed.lumps[i].name, original.lumps[i].name);
    const bool replaced = i == lump_index(original, map, "NODES") || i == lump_index(original, map, "VERTEXES");
    EXPECT_EQ(changed.lumps[i].data == original.lumps[i].data, !replaced)
        << "lump " << i << " " << original.lumps[i].name;
  }
  const VanillaNodes back = read_vanilla_nodes(changed, read_map(changed, "MAP05", "changed"), "changed");
  EXPECT_EQ(back.nodes.back().bbox[1][3], 12345);
  EXPECT_EQ(back.vertices.back().x, -7);
  EXPECT_EQ(back.vertices.size(), nodes.vertices.size());
}

TEST(DoomMap, MissingNodeLumpsAreInsertedInVanillaOrder) {
  SKIP_WITHOUT(kFreedoom2);
  Wad pwad = map01_pwad();
  const DoomMap map = read_map(pwad, "MAP01", "one.wad");
  const VanillaNodes nodes = read_vanilla_nodes(pwad, map, "one.wad");
  std::erase_if(pwad.lumps,
                [](const Lump& l) { return l.name == "SEGS" || l.name == "SSECTORS" || l.name == "NODES"; });
  replace_nodes(pwad, map, nodes);
  std::vector<std::string> names;
  for (const Lump& l : pwad.lumps) names.push_back(l.name);
  EXPECT_EQ(names, (std::vector<std::string>{"MAP01", "THINGS", "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS", "SSECTORS",
                                             "NODES", "SECTORS", "REJECT", "BLOCKMAP"}));
  EXPECT_EQ(read_vanilla_nodes(pwad, map, "one.wad").segs.size(), nodes.segs.size());
}

TEST(DoomMap, SingleMapPwadHoldsTheMarkerAndTheMapLumpsOnly) {
  SKIP_WITHOUT(kFreedoom1);
  const Wad wad = read_wad(kFreedoom1);
  const DoomMap map = read_map(wad, "E2M3", kFreedoom1);
  const Wad pwad = single_map_pwad(wad, map);
  EXPECT_FALSE(pwad.iwad);
  ASSERT_EQ(pwad.lumps.size(), 11u);
  EXPECT_EQ(pwad.lumps.front().name, "E2M3");
  EXPECT_EQ(pwad.lumps.back().name, "BLOCKMAP");
  EXPECT_EQ(map_names(pwad), std::vector<std::string>{"E2M3"});
  EXPECT_TRUE(pwad.lumps[1].data == wad.lumps[map.marker + 1].data);
}

// ---- tree statistics ----

namespace {

// Two one-sided linedefs and one two-sided: 4 sides.
DoomMap four_sided_map() {
  DoomMap map;
  map.vertices = {{0, 0}, {64, 0}, {64, 64}};
  map.linedefs = {{0, 1, 0, 0, 0, {0, kNoSidedef}}, {1, 2, 0, 0, 0, {1, kNoSidedef}}, {2, 0, 0, 0, 0, {2, 3}}};
  map.sidedefs.resize(4);
  map.sectors.resize(1);
  return map;
}

}  // namespace

TEST(DoomTreeStats, CountsSplitsAndSubsectorDepths) {
  VanillaNodes n;
  n.segs.resize(6);
  n.subsectors = {{2, 0}, {2, 2}, {2, 4}};
  // Root (node 1): node 0 on the right, subsector 2 on the left; node 0 holds subsectors 0 and 1.
  n.nodes.resize(2);
  n.nodes[0].child = {kSubsectorChild | 0, kSubsectorChild | 1};
  n.nodes[1].child = {0, kSubsectorChild | 2};
  const DoomTreeStats s = doom_tree_stats(four_sided_map(), n);
  EXPECT_EQ(s.segs, 6u);
  EXPECT_EQ(s.subsectors, 3u);
  EXPECT_EQ(s.nodes, 2u);
  EXPECT_EQ(s.splits, 2);
  EXPECT_EQ(s.max_depth, 2u);
  EXPECT_DOUBLE_EQ(s.mean_depth, 5.0 / 3.0);
}

TEST(DoomTreeStats, ASingleSubsectorHasDepthZero) {
  VanillaNodes n;
  n.segs.resize(4);
  n.subsectors = {{4, 0}};
  const DoomTreeStats s = doom_tree_stats(four_sided_map(), n);
  EXPECT_EQ(s.nodes, 0u);
  EXPECT_EQ(s.splits, 0);
  EXPECT_EQ(s.max_depth, 0u);
  EXPECT_EQ(s.mean_depth, 0.0);
}

TEST(DoomTreeStats, ACycleIsNotFollowed) {
  VanillaNodes n;
  n.subsectors = {{0, 0}};
  n.nodes.resize(2);
  n.nodes[0].child = {1, kSubsectorChild | 0};
  n.nodes[1].child = {0, 0};
  const DoomTreeStats s = doom_tree_stats(four_sided_map(), n);
  EXPECT_EQ(s.max_depth, 2u);
}

// ---- the structural check, on ZDBSP's nodes for Freedoom 2's MAP01 ----

namespace {

class DoomCheck : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!fs::exists(kFreedoom2) || std::system("command -v zdbsp > /dev/null 2>&1") != 0) return;
    const fs::path dir = fs::temp_directory_path() / ("bspbench_doom_zdbsp_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    write_wad((dir / "in.wad").string(), map01_pwad());
    const std::string cmd = "zdbsp -o " + (dir / "out.wad").string() + " " + (dir / "in.wad").string() + " > " +
                            (dir / "log").string() + " 2>&1";
    if (std::system(cmd.c_str()) == 0) {
      const Wad out = read_wad((dir / "out.wad").string());
      map_ = new DoomMap(read_map(out, "MAP01", "zdbsp output"));
      nodes_ = new VanillaNodes(read_vanilla_nodes(out, *map_, "zdbsp output"));
    }
    fs::remove_all(dir);
  }
  static void TearDownTestSuite() {
    delete map_;
    delete nodes_;
    map_ = nullptr;
    nodes_ = nullptr;
  }
  void SetUp() override {
    if (!map_) GTEST_SKIP() << "needs zdbsp and " << kFreedoom2;
  }

  std::uint16_t sector_of(const Seg& s) const {
    return map_->sidedefs[map_->linedefs[s.linedef].sidenum[s.side]].sector;
  }

  // Calls f(node, side, subsector) for every child that is a subsector until it returns true.
  static void for_leaf_children(const VanillaNodes& n, const std::function<bool(std::size_t, int, std::size_t)>& f) {
    for (std::size_t i = 0; i < n.nodes.size(); ++i)
      for (int side = 0; side < 2; ++side)
        if ((n.nodes[i].child[side] & kSubsectorChild) && f(i, side, n.nodes[i].child[side] & ~kSubsectorChild)) return;
  }

  static DoomMap* map_;
  static VanillaNodes* nodes_;
};

DoomMap* DoomCheck::map_ = nullptr;
VanillaNodes* DoomCheck::nodes_ = nullptr;

}  // namespace

TEST_F(DoomCheck, ZdbspNodesOfAFreedoomMapPass) {
  const DoomCheckReport r = check_doom_nodes(*map_, *nodes_);
  EXPECT_TRUE(r.ok()) << r.violations()
                      << " violations, first: " << (r.first_problems.empty() ? "" : r.first_problems[0]);
  EXPECT_LE(r.worst_side_distance, kDoomSideTolerance);
  EXPECT_GT(nodes_->nodes.size(), 100u);
}

TEST_F(DoomCheck, ZdbspNodesOfEveryFreedoom2MapPass) {
  const fs::path dir = bsp::testing::fresh_test_dir("bspbench_doom_zdbsp");
  const std::string out = (dir / "out.wad").string();
  ASSERT_EQ(std::system(("zdbsp -o " + out + " " + kFreedoom2 + " > " + (dir / "log").string() + " 2>&1").c_str()), 0);
  const Wad wad = read_wad(out);
  fs::remove_all(dir);
  ASSERT_EQ(map_names(wad).size(), 32u);
  for (const std::string& name : map_names(wad)) {
    const DoomMap map = read_map(wad, name, out);
    const DoomCheckReport r = check_doom_nodes(map, read_vanilla_nodes(wad, map, out));
    EXPECT_TRUE(r.ok()) << name << ": " << r.violations() << " violations, first: " << r.first_problems.front();
  }
}

// The shipped nodes hold every structural property; what they break (a subsector mixing sectors
// where a map's sidedefs name the wrong sector, a side distance beyond the tolerance) is geometry.
TEST(DoomCheckShipped, EveryFreedoomTreeIsStructurallySound) {
  SKIP_WITHOUT(kFreedoom1);
  SKIP_WITHOUT(kFreedoom2);
  for (const std::string& file : {kFreedoom1, kFreedoom2}) {
    const Wad wad = read_wad(file);
    for (const std::string& name : map_names(wad)) {
      const DoomMap map = read_map(wad, name, file);
      const DoomCheckReport r = check_doom_nodes(map, read_vanilla_nodes(wad, map, file));
      EXPECT_EQ(r.violations(), r.wrong_side_segs + r.mixed_sector_subsectors) << file << " " << name;
      EXPECT_EQ(r.non_convex_segs, 0u) << file << " " << name;
    }
  }
}

TEST_F(DoomCheck, CatchesASegMovedToASubsectorOfAnotherSector) {
  VanillaNodes n = *nodes_;
  const auto one_sector = [&](const Subsector& s) {
    for (std::size_t k = s.first; k < std::size_t{s.first} + s.count; ++k)
      if (sector_of(n.segs[k]) != sector_of(n.segs[s.first])) return false;
    return s.count >= 2;
  };
  const Subsector* a = nullptr;
  const Subsector* b = nullptr;
  for (const Subsector& s : n.subsectors) {
    if (!one_sector(s)) continue;
    if (!a)
      a = &s;
    else if (sector_of(n.segs[s.first]) != sector_of(n.segs[a->first])) {
      b = &s;
      break;
    }
  }
  ASSERT_TRUE(a && b);
  std::swap(n.segs[a->first], n.segs[b->first]);
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.mixed_sector_subsectors, 2u);
  EXPECT_FALSE(r.ok());
}

TEST_F(DoomCheck, CatchesAnUnreachableSubsector) {
  VanillaNodes n = *nodes_;
  for_leaf_children(n, [&](std::size_t node, int side, std::size_t leaf) {
    n.nodes[node].child[side] = static_cast<std::uint16_t>(kSubsectorChild | (leaf == 0 ? 1 : 0));
    return true;
  });
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.unreachable_subsectors, 1u);
  EXPECT_FALSE(r.ok());
}

TEST_F(DoomCheck, CatchesAChildPointingTwiceAtOneSubsector) {
  VanillaNodes n = *nodes_;
  bool mutated = false;
  for (NodeRecord& node : n.nodes)
    if (!mutated && (node.child[0] & node.child[1] & kSubsectorChild)) {
      node.child[1] = node.child[0];
      mutated = true;
    }
  ASSERT_TRUE(mutated);
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.repeated_subsectors, 1u);
  EXPECT_EQ(r.unreachable_subsectors, 1u);
}

TEST_F(DoomCheck, CatchesANodeReachedTwice) {
  VanillaNodes n = *nodes_;
  NodeRecord& root = n.nodes.back();
  ASSERT_FALSE(root.child[0] & kSubsectorChild);
  root.child[1] = root.child[0];
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.repeated_nodes, 1u);
  EXPECT_GE(r.unreachable_nodes + r.unreachable_subsectors, 1u);
}

TEST_F(DoomCheck, CatchesAFlippedPartition) {
  VanillaNodes n = *nodes_;
  n.nodes.back().dx = static_cast<std::int16_t>(-n.nodes.back().dx);
  n.nodes.back().dy = static_cast<std::int16_t>(-n.nodes.back().dy);
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_GT(r.wrong_side_segs, n.segs.size() / 4);
  EXPECT_GT(r.worst_side_distance, 100.0);
}

TEST_F(DoomCheck, CatchesASegVertexMovedFiveUnitsAcrossItsPartition) {
  VanillaNodes n = *nodes_;
  bool moved = false;
  // An axis-parallel partition with an endpoint of one of its leaf child's segs on it, so the move is exactly 5.
  for_leaf_children(n, [&](std::size_t node, int side, std::size_t leaf) {
    const NodeRecord& p = n.nodes[node];
    if (p.dx != 0 && p.dy != 0) return false;
    const Subsector& s = n.subsectors[leaf];
    for (std::size_t k = s.first; k < std::size_t{s.first} + s.count; ++k) {
      const DoomVertex v = n.vertices[n.segs[k].v1];
      if ((v.x - p.x) * p.dy - (v.y - p.y) * p.dx != 0) continue;
      // (-dy, dx) points to the left of the partition, away from child[0].
      const int sign = side == 0 ? 1 : -1;
      const int ux = p.dy == 0 ? 0 : (p.dy > 0 ? -1 : 1), uy = p.dx == 0 ? 0 : (p.dx > 0 ? 1 : -1);
      n.vertices.push_back(
          {static_cast<std::int16_t>(v.x + 5 * sign * ux), static_cast<std::int16_t>(v.y + 5 * sign * uy)});
      n.segs[k].v1 = static_cast<std::uint16_t>(n.vertices.size() - 1);
      return moved = true;
    }
    return false;
  });
  ASSERT_TRUE(moved);
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_GE(r.wrong_side_segs, 1u);
  EXPECT_DOUBLE_EQ(r.worst_side_distance, 5.0);
}

TEST_F(DoomCheck, CatchesASegEndingBehindAnotherSegOfItsSubsector) {
  VanillaNodes n = *nodes_;
  bool moved = false;
  // Seg a of an axis-parallel linedef: a point 5 units behind it (on its left, away from its
  // sector) becomes the end of the subsector's next seg.
  for (const Subsector& s : n.subsectors) {
    if (moved || s.count < 2) continue;
    const Seg& a = n.segs[s.first];
    const DoomVertex p = n.vertices[a.v1], q = n.vertices[a.v2];
    if (p.x != q.x && p.y != q.y) continue;
    const int ux = q.y == p.y ? 0 : (q.y > p.y ? -1 : 1), uy = q.x == p.x ? 0 : (q.x > p.x ? 1 : -1);
    n.vertices.push_back(
        {static_cast<std::int16_t>((p.x + q.x) / 2 + 5 * ux), static_cast<std::int16_t>((p.y + q.y) / 2 + 5 * uy)});
    n.segs[s.first + 1].v2 = static_cast<std::uint16_t>(n.vertices.size() - 1);
    moved = true;
  }
  ASSERT_TRUE(moved);
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_GE(r.non_convex_segs, 1u);
  EXPECT_GE(r.worst_convexity_distance, 4.0);
}

TEST_F(DoomCheck, CatchesBadSegReferences) {
  VanillaNodes n = *nodes_;
  n.segs[0].v1 = static_cast<std::uint16_t>(n.vertices.size());
  n.segs[1].linedef = static_cast<std::uint16_t>(map_->linedefs.size());
  n.segs[2].side = 2;
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.bad_seg_vertices, 1u);
  EXPECT_EQ(r.bad_seg_linedefs, 1u);
  EXPECT_EQ(r.bad_seg_sides, 1u);
  VanillaNodes one_sided = *nodes_;
  for (Seg& s : one_sided.segs)
    if (map_->linedefs[s.linedef].sidenum[1] == kNoSidedef) {
      s.side = 1;
      break;
    }
  EXPECT_EQ(check_doom_nodes(*map_, one_sided).bad_seg_sides, 1u);
}

TEST_F(DoomCheck, CatchesSegsCoveredTwiceOrNotAtAll) {
  VanillaNodes n = *nodes_;
  ASSERT_EQ(n.subsectors[1].first, n.subsectors[0].first + n.subsectors[0].count);
  ++n.subsectors[0].count;
  const DoomCheckReport overlap = check_doom_nodes(*map_, n);
  EXPECT_EQ(overlap.overlapping_segs, 1u);
  n = *nodes_;
  n.segs.push_back(n.segs.back());
  EXPECT_EQ(check_doom_nodes(*map_, n).uncovered_segs, 1u);
  n = *nodes_;
  n.subsectors[3].count = 0;
  const DoomCheckReport empty = check_doom_nodes(*map_, n);
  EXPECT_EQ(empty.empty_subsectors, 1u);
  EXPECT_EQ(empty.uncovered_segs, nodes_->subsectors[3].count);
}

TEST_F(DoomCheck, CatchesOutOfRangeChildrenAndDegeneratePartitions) {
  VanillaNodes n = *nodes_;
  n.nodes[0].child[0] = static_cast<std::uint16_t>(kSubsectorChild | n.subsectors.size());
  n.nodes[1].dx = n.nodes[1].dy = 0;
  const DoomCheckReport r = check_doom_nodes(*map_, n);
  EXPECT_EQ(r.bad_children, 1u);
  EXPECT_EQ(r.degenerate_partitions, 1u);
}
