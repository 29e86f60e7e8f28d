// bspbench doom from the command line: our trees and ZDBSP's on real Freedoom maps, the PWADs it
// writes read back whole, and bad WADs refused with one line naming the lump, exit 2, no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "io/doom_map.h"
#include "io/wad.h"

using namespace bsp;
using namespace bsp::testing;

namespace {

const std::filesystem::path kFreedoom2 = "/usr/share/games/doom/freedoom2.wad";

class DoomCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kFreedoom2)) GTEST_SKIP() << kFreedoom2 << " is missing (apt-get install freedoom)";
    dir_ = fresh_test_dir("doom_cli");
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  std::filesystem::path dir_;
};

void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

}  // namespace

TEST_F(DoomCli, PresetsBuildProvedNodesAndWriteReadablePwads) {
  const auto r = run_bspbench("doom --iwad " + kFreedoom2.string() + " --maps MAP01,MAP02 --heuristics doom-splits,crystal:candidates=8 "
                              "--views 2 --out " + (dir_ / "out").string() + " --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::size_t ours = 0;
  for (const auto& run : j["runs"]) {
    if (run["kind"] != "heuristic") continue;
    ++ours;
    EXPECT_TRUE(run["ok"].get<bool>()) << run.dump();
    EXPECT_EQ(run["check_violations"], 0u);
    EXPECT_EQ(run["order"]["violations"], 0u);
    EXPECT_GT(run["order"]["pairs_checked"].get<std::uint64_t>(), 1000u);
    EXPECT_GE(run["splits"].get<std::int64_t>(), 0);
  }
  EXPECT_EQ(ours, 4u);
  // Progress goes to stderr, not into the JSON: off a terminal, one final plain line (the runs
  // take well under the 10 s between plain lines) counting every run, the shipped nodes' included.
  EXPECT_EQ(r.err.rfind("doom: 6/6 runs, ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const char* label : {"doom-splits", "crystal{candidates=8}"})
    for (const char* map : {"MAP01", "MAP02"}) {
      const auto file = dir_ / "out" / label / (std::string(map) + ".wad");
      ASSERT_TRUE(std::filesystem::exists(file)) << file;
      const Wad wad = read_wad(file.string());
      const DoomMap m = read_map(wad, map, file.string());
      EXPECT_GT(read_vanilla_nodes(wad, m, file.string()).segs.size(), m.linedefs.size());
    }
}

TEST_F(DoomCli, ShippedNodesAreMeasuredByTheSameParser) {
  const auto r = run_bspbench("doom --iwad " + kFreedoom2.string() + " --maps MAP01 --heuristics first --views 1 --json", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  bool shipped = false;
  for (const auto& t : j["totals"])
    if (t["builder"] == "shipped") {
      shipped = true;
      EXPECT_GT(t["segs"].get<std::uint64_t>(), 0u);
      EXPECT_GT(t["nodes"].get<std::uint64_t>(), 0u);
    }
  EXPECT_TRUE(shipped);
}

TEST_F(DoomCli, TruncatedLumpIsNamedAndNothingIsWritten) {
  Wad wad = read_wad(kFreedoom2.string());
  const DoomMap map = read_map(wad, "MAP01", kFreedoom2.string());
  Wad one = single_map_pwad(wad, map);
  for (Lump& l : one.lumps)
    if (l.name == "LINEDEFS") l.data.resize(l.data.size() - 3);
  const auto bad = dir_ / "bad.wad";
  write_bytes(bad, wad_bytes(one));
  const auto r = run_bspbench("doom --iwad " + bad.string() + " --heuristics crystal --out " + (dir_ / "out").string(), dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("LINEDEFS"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out"));
}

TEST_F(DoomCli, DirectoryPastTheEndIsNamed) {
  std::string bytes = wad_bytes(single_map_pwad(read_wad(kFreedoom2.string()),
                                                read_map(read_wad(kFreedoom2.string()), "MAP01", kFreedoom2.string())));
  bytes.resize(bytes.size() - 20);
  const auto bad = dir_ / "short.wad";
  write_bytes(bad, bytes);
  const auto r = run_bspbench("doom --iwad " + bad.string() + " --heuristics crystal", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
}

TEST_F(DoomCli, UnknownMapHeuristicAndBuilderAreUsageOrInputErrors) {
  EXPECT_EQ(run_bspbench("doom --iwad " + kFreedoom2.string() + " --maps MAP99 --heuristics crystal", dir_).code, 2);
  EXPECT_EQ(run_bspbench("doom --iwad " + kFreedoom2.string() + " --heuristics nosuch", dir_).code, 2);
  EXPECT_EQ(run_bspbench("doom --iwad " + kFreedoom2.string() + " --heuristics crystal --builders nosuch", dir_).code, 2);
  EXPECT_EQ(run_bspbench("doom --iwad " + kFreedoom2.string() + " --heuristics crystal:nosuch=1", dir_).code, 2);
}
