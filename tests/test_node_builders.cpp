// External node builders (experiments/doom/node_builders.h) on a map small enough to write here: an L-shaped
// room, which is not convex, so every builder must split it with at least one node.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "common/errors.h"
#include "experiments/doom/node_builders.h"

namespace fs = std::filesystem;
using bsp::experiments::find_builder;
using bsp::experiments::known_builders;
using bsp::experiments::run_node_builder;

namespace {

using Bytes = std::vector<std::uint8_t>;

void put16(Bytes& b, int v) {
  b.push_back(static_cast<std::uint8_t>(v & 0xff));
  b.push_back(static_cast<std::uint8_t>((v >> 8) & 0xff));
}
void put32(Bytes& b, std::uint32_t v) {
  put16(b, static_cast<int>(v & 0xffff));
  put16(b, static_cast<int>(v >> 16));
}
void put_name(Bytes& b, const std::string& name) {
  for (size_t i = 0; i < 8; ++i) b.push_back(i < name.size() ? static_cast<std::uint8_t>(name[i]) : 0);
}

void write_pwad(const fs::path& path, const std::vector<std::pair<std::string, Bytes>>& lumps) {
  Bytes body, directory;
  for (const auto& [name, data] : lumps) {
    put32(directory, static_cast<std::uint32_t>(12 + body.size()));
    put32(directory, static_cast<std::uint32_t>(data.size()));
    put_name(directory, name);
    body.insert(body.end(), data.begin(), data.end());
  }
  Bytes header{'P', 'W', 'A', 'D'};
  put32(header, static_cast<std::uint32_t>(lumps.size()));
  put32(header, static_cast<std::uint32_t>(12 + body.size()));
  std::ofstream out(path, std::ios::binary);
  for (const Bytes* part : {&header, &body, &directory}) out.write(reinterpret_cast<const char*>(part->data()), part->size());
}

// MAP01: one sector, an L of six one-sided lines walked clockwise so their right sides face in.
void write_l_room(const fs::path& path) {
  const int xy[6][2] = {{0, 0}, {256, 0}, {256, 128}, {128, 128}, {128, 256}, {0, 256}};
  Bytes things, lines, sides, vertices, sector;
  for (const auto& v : xy) put16(vertices, v[0]), put16(vertices, v[1]);
  for (int i = 0; i < 6; ++i) {
    for (int v : {(i + 1) % 6, i, 1, 0, 0, i, 0xffff}) put16(lines, v);  // v1 v2 flags special tag right left
    put16(sides, 0), put16(sides, 0), put_name(sides, "-"), put_name(sides, "-"), put_name(sides, "STARTAN3");
    put16(sides, 0);
  }
  put16(sector, 0), put16(sector, 128), put_name(sector, "FLOOR4_8"), put_name(sector, "CEIL3_5");
  put16(sector, 160), put16(sector, 0), put16(sector, 0);
  for (int v : {64, 64, 0, 1, 7}) put16(things, v);  // player 1 start
  write_pwad(path, {{"MAP01", {}}, {"THINGS", things}, {"LINEDEFS", lines}, {"SIDEDEFS", sides},
                    {"VERTEXES", vertices}, {"SEGS", {}}, {"SSECTORS", {}}, {"NODES", {}}, {"SECTORS", sector},
                    {"REJECT", {}}, {"BLOCKMAP", {}}});
}

// The lumps of a WAD by name (the last of each name).
std::map<std::string, std::string> lumps_of(const fs::path& path) {
  const std::string wad = bsp::testing::slurp(path);
  std::map<std::string, std::string> lumps;
  if (wad.size() < 12) return lumps;
  auto u32 = [&](size_t at) {
    std::uint32_t v;
    std::memcpy(&v, wad.data() + at, 4);
    return v;
  };
  for (std::uint32_t i = 0, table = u32(8); i < u32(4) && table + 16 * i + 16 <= wad.size(); ++i) {
    const size_t entry = table + 16 * i;
    const std::string name(wad.data() + entry + 8, strnlen(wad.data() + entry + 8, 8));
    lumps[name] = wad.substr(u32(entry), u32(entry + 4));
  }
  return lumps;
}

class NodeBuilders : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (find_builder(GetParam()).path.empty()) GTEST_SKIP() << GetParam() << " is not installed (apt-get install " << GetParam() << ")";
    dir_ = bsp::testing::fresh_test_dir("node_builders");
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

}  // namespace

TEST(NodeBuilderNames, AreZdbspAndGlbsp) {
  EXPECT_EQ(known_builders(), (std::vector<std::string>{"zdbsp", "glbsp"}));
}

TEST(NodeBuilderNames, AnUnknownOneIsAUsageErrorListingTheKnownOnes) {
  try {
    run_node_builder("bsp-w32", "in.wad", "out.wad", 10);
    FAIL() << "no UsageError";
  } catch (const bsp::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("bsp-w32"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("zdbsp, glbsp"), std::string::npos) << e.what();
  }
  EXPECT_THROW(find_builder("bsp-w32"), bsp::UsageError);
}

TEST_P(NodeBuilders, ReportItsVersion) {
  const std::string version = find_builder(GetParam()).version;
  std::string upper = version;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  EXPECT_NE(upper.find(GetParam() == "zdbsp" ? "ZDBSP" : "GLBSP"), std::string::npos) << version;
}

TEST_P(NodeBuilders, WriteVanillaNodesThatSplitANonConvexRoom) {
  write_l_room(dir_ / "in.wad");
  const auto run = run_node_builder(GetParam(), (dir_ / "in.wad").string(), (dir_ / "out.wad").string(), 60);
  ASSERT_TRUE(run.ok()) << run.failure() << "\n" << run.log;
  EXPECT_EQ(run.failure(), "");
  EXPECT_GE(run.cpu_seconds, 0.0);
  EXPECT_GT(run.wall_seconds, 0.0);
  const auto lumps = lumps_of(dir_ / "out.wad");
  ASSERT_TRUE(lumps.count("NODES")) << "no NODES lump in " << run.output_path;
  const std::string& nodes = lumps.at("NODES");
  EXPECT_GE(nodes.size(), 28u);
  EXPECT_EQ(nodes.size() % 28, 0u) << "not vanilla 28-byte nodes";
  EXPECT_GE(lumps.at("SSECTORS").size(), 2 * 4u);
  EXPECT_EQ(lumps.at("SEGS").size() % 12, 0u);
}

TEST_P(NodeBuilders, FailOnAFileThatIsNoWadWithAResultNotAnException) {
  std::ofstream(dir_ / "junk.wad") << "this is not a WAD file";
  const auto run = run_node_builder(GetParam(), (dir_ / "junk.wad").string(), (dir_ / "out.wad").string(), 60);
  EXPECT_FALSE(run.ok());
  EXPECT_FALSE(run.timed_out);
  EXPECT_EQ(run.failure().rfind(GetParam() + " ", 0), 0u) << run.failure();
}

TEST_P(NodeBuilders, AreKilledAtTheTimeout) {
  write_l_room(dir_ / "in.wad");
  const auto run = run_node_builder(GetParam(), (dir_ / "in.wad").string(), (dir_ / "out.wad").string(), 0);
  EXPECT_TRUE(run.timed_out);
  EXPECT_FALSE(run.ok());
  EXPECT_NE(run.failure().find("timed out"), std::string::npos) << run.failure();
}

TEST_P(NodeBuilders, RejectAMissingInputWithAnInputErrorNamingIt) {
  const std::string missing = (dir_ / "missing.wad").string();
  try {
    run_node_builder(GetParam(), missing, (dir_ / "out.wad").string(), 60);
    FAIL() << "no InputError";
  } catch (const bsp::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Installed, NodeBuilders, ::testing::Values("zdbsp", "glbsp"));
