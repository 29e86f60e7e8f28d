// The sweep commands of the real bspbench binary: a suite run as three shards under GNU parallel
// merges to the unsharded report in every deterministic field, and bad shard sets are rejected;
// `report` renders every plot it links as a valid PNG, merges' included; a merge run's command
// repeats it; `regress` exits 0 on an identical report, 1 on a changed result and 2 on bad input,
// and catches a planted slowdown of one heuristic's builds and merges. Suites users write as JSON
// run like the built-in ones, journal by their text, and bad ones are one-line errors.
#include <gtest/gtest.h>

#include "cli_runner.h"
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "mesh_scenes.h"
#include "results/record.h"
#include "results/report.h"
#include "suite/suite_file.h"
#include "sweep/runner.h"

using namespace bsp::results;
using namespace bsp::sweep;
namespace fs = std::filesystem;

namespace {

using bsp::testing::slurp;

class SweepCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = bsp::testing::fresh_test_dir("bspbench_sweepcli");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs a shell command line with stdout and stderr captured; returns the exit status.
  int shell(const std::string& line) {
    const std::string cmd = "cd " + dir_.string() + " && " + line + " > stdout 2> stderr";
    const int status = std::system(cmd.c_str());
    out_ = slurp(dir_ / "stdout");
    err_ = slurp(dir_ / "stderr");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  int bspbench(const std::string& args) { return shell(std::string(BSPBENCH_EXE) + " " + args); }

  // A small report made through the library: two scenes, two heuristics, two sizes, two seeds; and
  // merges of one solid pair, two heuristics, two operations, two sizes, two seeds.
  fs::path small_report() {
    const bsp::suite::Suite suite = bsp::suite::parse_suite_file(
        R"({"name": "tiny", "summary": "test suite",
            "blocks": [{"scenes": ["random-triangles", "random-disjoint"], "heuristics": ["first", "random"],
                        "sizes": [40, 80], "seeds": [1, 2]}],
            "merges": [{"pairs": ["spheres"], "heuristics": ["first", "naylor"], "ops": ["union", "difference"],
                        "sizes": [50, 100], "seeds": [1, 2], "points": 500}]})",
        "tiny.json");
    SweepOptions o;
    o.journal_dir = (dir_ / "journal").string();
    const fs::path path = dir_ / "small.json";
    write_report(path.string(), run_sweep(suite, o));
    return path;
  }

  fs::path dir_;
  std::string out_, err_;
};

// PNG signature (ISO/IEC 15948 §5.2) and a nonzero width and height in the IHDR chunk that must
// follow it.
bool is_png(const fs::path& p) {
  const std::string bytes = slurp(p);
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0)
    return false;
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return be32(16) > 0 && be32(20) > 0;
}

}  // namespace

TEST_F(SweepCli, ThreeShardsUnderGnuParallelMergeToTheUnshardedReport) {
  ASSERT_NE(bspbench("sweep --suite smoke --threads 2 --out full.json"), 2) << err_;
  ASSERT_EQ(shell("parallel --will-cite --halt now,fail=1 '" + std::string(BSPBENCH_EXE) +
                  " sweep --suite smoke --threads 1 --shard {}/3 --out shard{}.json; test $? -ne 2' ::: 0 1 2"),
            0)
      << err_;
  ASSERT_EQ(bspbench("merge-reports --out merged.json shard0.json shard1.json shard2.json"), 0) << err_;
  const auto full = read_report((dir_ / "full.json").string());
  const auto merged = read_report((dir_ / "merged.json").string());
  EXPECT_EQ(merged["shards"].size(), 3u);
  EXPECT_GT(full["runs"].size(), 100u);
  EXPECT_TRUE(deterministic_view(merged) == deterministic_view(full)) << "merged and unsharded reports differ";

  EXPECT_EQ(bspbench("merge-reports --out bad.json shard0.json shard1.json shard1.json"), 2);
  EXPECT_NE(err_.find("twice"), std::string::npos) << err_;
  EXPECT_EQ(bspbench("merge-reports --out bad.json shard0.json shard2.json"), 2);
  EXPECT_NE(err_.find("missing shard(s) 1/3"), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(dir_ / "bad.json"));
}

TEST_F(SweepCli, ReportRendersEveryLinkedPlotAsAValidPng) {
  const fs::path report = small_report();
  ASSERT_EQ(bspbench("report --in " + report.string() + " --out html"), 0) << err_;
  const std::string page = slurp(dir_ / "html" / "index.html");
  const std::regex img("<img src='([^']+)'");
  std::size_t images = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), img); it != std::sregex_iterator(); ++it) {
    ++images;
    const fs::path png = dir_ / "html" / (*it)[1].str();
    EXPECT_TRUE(fs::exists(png) && fs::file_size(png) > 0 && is_png(png)) << png;
  }
  // The scoreboard; a Pareto view, a scaling plot and a cost-model scatter for each of the two scenes;
  // merge time and result sizes for the pair.
  EXPECT_EQ(images, 9u);
  EXPECT_NE(page.find("Set operations: merge cost by heuristic"), std::string::npos);
  EXPECT_NE(page.find("naylor's rank"), std::string::npos);
  // A corrupted image is caught by the check above.
  std::ofstream(dir_ / "fake.png") << "\x89PNG\r\n\x1a\nnot really";
  EXPECT_FALSE(is_png(dir_ / "fake.png"));
  std::ofstream(dir_ / "bad.json") << "[1, 2]";
  EXPECT_EQ(bspbench("report --in bad.json --out html2"), 2);
}

// A merge run's command repeats the run: `bspbench merge` with it reports the same merge cost,
// result size and volume as the sweep recorded.
TEST_F(SweepCli, MergeRunCommandRepeatsTheRun) {
  const auto report = read_report(small_report().string());
  std::size_t checked = 0;
  for (const auto& run : report["runs"]) {
    if (run["id"].value("kind", "") != "merge" || run["id"]["n"] != 100 || run["id"]["seed"] != 2) continue;
    const std::string command = run["id"]["command"];
    ASSERT_EQ(command.rfind("bspbench merge ", 0), 0u) << command;
    ASSERT_EQ(bspbench(command.substr(9) + " --json"), 0) << command << "\n" << err_;
    const auto out = nlohmann::json::parse(out_);
    EXPECT_EQ(out["merge"]["partition_calls"], run["metrics"]["partition_calls"]) << command;
    EXPECT_EQ(out["merge"]["after"]["nodes"], run["metrics"]["after_nodes"]) << command;
    EXPECT_EQ(out["merge"]["before"]["nodes"], run["metrics"]["before_nodes"]) << command;
    EXPECT_EQ(out["check"]["tree_volume"], run["metrics"]["result_volume"]) << command;
    EXPECT_EQ(out["check"]["mismatches"], run["validation"]["mismatches"]) << command;
    ++checked;
  }
  EXPECT_EQ(checked, 4u);  // 2 heuristics x 2 operations
}

// A drawing run's command prints the run's metrics, all of them equal, for a 3D scene, a 2D one
// (whose query costs are undefined, so neither prints them) and an incremental build.
TEST_F(SweepCli, DrawRunCommandRepeatsTheRunIn3DIn2DAndIncrementally) {
  std::ofstream(dir_ / "draw.json") << R"({"name": "draw", "blocks": [
      {"scenes": ["city", "random-segments"], "heuristics": ["weighted"], "sizes": [100], "seeds": [2]},
      {"scenes": ["city"], "incremental": true, "sizes": [100], "seeds": [2]}]})";
  ASSERT_EQ(bspbench("sweep --suite draw.json --out draw-report.json --journal-dir j"), 0) << err_;
  const auto report = read_report((dir_ / "draw-report.json").string());
  ASSERT_EQ(report["runs"].size(), 3u);
  for (const auto& run : report["runs"]) {
    const std::string command = run["id"]["command"];
    ASSERT_EQ(command.rfind("bspbench build ", 0), 0u) << command;
    ASSERT_EQ(bspbench(command.substr(9) + " --json"), 0) << command << "\n" << err_;
    const auto out = nlohmann::json::parse(out_);
    for (const auto& [k, v] : run["metrics"].items()) EXPECT_EQ(out[k], v) << command << ": " << k;
    EXPECT_EQ(out.contains("e_line"), run["metrics"].contains("e_line")) << command;
  }
}

TEST_F(SweepCli, RegressExitsZeroOnIdenticalOneOnChangedAndTwoOnBadInput) {
  const fs::path base = small_report();
  EXPECT_EQ(bspbench("regress --baseline " + base.string() + " --current " + base.string()), 0) << out_ << err_;
  EXPECT_NE(out_.find("no regression"), std::string::npos) << out_;

  nlohmann::json changed = read_report(base.string());
  auto drawn = std::find_if(changed["runs"].begin(), changed["runs"].end(),
                           [](const nlohmann::json& r) { return r["id"]["kind"] == "draw"; });
  ASSERT_NE(drawn, changed["runs"].end());
  auto& fragments = (*drawn)["metrics"]["fragments"];
  fragments = fragments.get<std::uint64_t>() + 1;
  write_report((dir_ / "changed.json").string(), changed);
  EXPECT_EQ(bspbench("regress --baseline " + base.string() + " --current changed.json"), 1);
  EXPECT_NE(out_.find("metrics.fragments"), std::string::npos) << out_;

  std::ofstream(dir_ / "garbage.json") << "{\"schema\": \"bspbench-report\", \"version\": 1}";
  EXPECT_EQ(bspbench("regress --baseline " + base.string() + " --current garbage.json"), 2);
  EXPECT_EQ(bspbench("regress --baseline " + base.string() + " --current " + base.string() + " --time-tolerance 1"), 2);
}

// The gate on real sweeps: the smoke suite run twice, the second with one heuristic's timed builds
// planted PLANT_FACTOR times slower (BSPBENCH_PLANT_SLOWDOWN, experiments/timing.h). Every group of that
// heuristic (one per scene) fails as slower, and no other group does (results are the gate's other
// half, tested elsewhere). A bad planting value is a one-line usage error.
TEST_F(SweepCli, PlantedSlowdownOfOneHeuristicFailsExactlyItsGroups) {
  constexpr const char* kPlant = "naylor:2";
  ASSERT_EQ(bspbench("sweep --suite smoke --threads 2 --out base.json --journal-dir j"), 0) << err_;
  ASSERT_EQ(shell(std::string("BSPBENCH_PLANT_SLOWDOWN=") + kPlant + " " + BSPBENCH_EXE +
                  " sweep --suite smoke --threads 2 --out planted.json --journal-dir j"),
            0)
      << err_;
  const auto planted = read_report((dir_ / "planted.json").string());
  EXPECT_EQ(planted["shards"][0]["planted_slowdown"]["heuristic"], "naylor");
  EXPECT_EQ(bspbench("regress --baseline base.json --current planted.json"), 1) << out_;
  // Drawing groups are scene x heuristic x shape, merge groups pair x heuristic x operation.
  std::set<std::string> failed_groups;
  std::istringstream lines(out_);
  for (std::string line; std::getline(lines, line);) {
    const bool merge = line.find("timings.merge_cpu_samples") != std::string::npos;
    if (!merge && line.find("timings.build_cpu_samples") == std::string::npos) continue;
    // A note is no failure: a group that ran 1.5x faster in one of the two sweeps (a loaded machine
    // during the other) is listed for information, and only a speed-up can be a note.
    if (line.rfind("note", 0) == 0) {
      EXPECT_NE(line.find("faster"), std::string::npos) << line;
      continue;
    }
    EXPECT_EQ(line.rfind("FAIL     slower", 0), 0u) << line;
    std::istringstream words(line.substr(line.find("slower") + 6));
    std::string scene, heuristic, shape;
    words >> scene >> heuristic >> shape;
    EXPECT_EQ(heuristic, "naylor") << line;
    failed_groups.insert(scene + " " + shape);
  }
  std::set<std::string> groups;
  for (const auto& r : planted["runs"]) {
    const auto& id = r["id"];
    groups.insert(id["scene"].get<std::string>() + " " + id.value("operation", id["shape"].get<std::string>()));
  }
  EXPECT_EQ(failed_groups, groups) << out_;

  EXPECT_EQ(shell(std::string("BSPBENCH_PLANT_SLOWDOWN=naylor ") + BSPBENCH_EXE + " sweep --suite smoke --out x.json"), 2);
  EXPECT_NE(err_.find("BSPBENCH_PLANT_SLOWDOWN"), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

// The report's 2D segment and Doom sections, from a hand-made report whose answers are known: the
// random autopartition stays under n + 2n ln n at both sizes; doom-depth beats ZDBSP on depth with
// fewer splits; doom-splits beats ZDBSP's CPU time but is not judged against ZokumBSP's total,
// which is for all 68 maps, nor is doom-search, whose CPU time is judged against 10 times ZDBSP's;
// the shipped nodes' violations are counted. Every linked plot is a PNG.
TEST_F(SweepCli, ReportRendersTheSegmentBoundAndDoomSections) {
  nlohmann::json runs = nlohmann::json::array();
  const auto segment_run = [&](int n, const std::string& heuristic, const std::string& shape, int seed, int fragments) {
    runs.push_back({{"key", std::to_string(runs.size())},
                    {"id", {{"kind", "draw"}, {"scene", "random-segments"}, {"n", n}, {"n_polygons", n},
                            {"scene_params", {{"n", n}, {"seed", seed}}}, {"heuristic", heuristic}, {"shape", shape},
                            {"seed", seed}, {"command", "bspbench build --scene random-segments --n " + std::to_string(n)}}},
                    {"metrics", {{"fragments", fragments}, {"max_depth", 20}, {"mean_depth", 9.5}}},
                    {"invariants", {{"violations", 0}, {"first_problems", nlohmann::json::array()}}},
                    {"validation", nullptr},
                    {"timings", {{"build_cpu_samples", {0.001, 0.001}}, {"build_cpu_seconds", 0.001}}},
                    {"calibration_seconds", 0.01}});
  };
  segment_run(100, "random", "strict", 1, 150);
  segment_run(100, "random", "strict", 2, 160);
  segment_run(1000, "random", "strict", 1, 2000);
  segment_run(1000, "random", "strict", 2, 2100);
  segment_run(1000, "crystal", "leafy", 1, 1500);
  // Per map: splits, max depth, CPU seconds (none for the shipped nodes), structural violations.
  const auto doom_run = [&](const std::string& map, const std::string& name, const std::string& kind, int splits,
                            int max_depth, double cpu, int violations) {
    nlohmann::json timings = nlohmann::json::object();
    if (kind == "heuristic") timings = {{"doom_cpu_samples", {cpu, cpu}}, {"doom_cpu_seconds", cpu}};
    if (kind == "external") timings = {{"builder_cpu_samples", {cpu, cpu, cpu}}};
    runs.push_back({{"key", std::to_string(runs.size())},
                    {"id", {{"kind", "doom"}, {"scene", "freedoom2.wad"}, {"iwad", "freedoom2.wad"}, {"map", map},
                            {"builder", name}, {"builder_kind", kind}, {"shape", "leafy"}, {"n", 0}, {"n_polygons", 1000},
                            {"scene_params", nlohmann::json::object()},
                            {"preset", kind == "heuristic" ? nlohmann::json(name) : nullptr},
                            {"heuristic", name}, {"seed", 1}, {"command", "bspbench doom --maps " + map}}},
                    {"metrics", {{"segs", 1000 + splits}, {"subsectors", 300}, {"nodes", 299}, {"splits", splits},
                                 {"max_depth", max_depth}, {"mean_depth", max_depth / 2.0}}},
                    {"invariants", {{"violations", violations}, {"first_problems", nlohmann::json::array()},
                                    {"worst_side_distance", 0.5}, {"worst_convexity_distance", 0.5}}},
                    {"validation", kind == "heuristic" ? nlohmann::json{{"violations", 0}, {"rays", 100}} : nullptr},
                    {"timings", timings},
                    {"calibration_seconds", 0.01}});
  };
  for (const std::string map : {"MAP01", "MAP02"}) {
    doom_run(map, "doom-splits", "heuristic", 100, 20, 0.01, 0);
    doom_run(map, "doom-depth", "heuristic", 150, 10, 0.01, 0);
    doom_run(map, "doom-search", "heuristic", 80, 35, 0.1, 0);
    doom_run(map, "zdbsp", "external", 200, 12, 0.02, 0);
    doom_run(map, "shipped", "shipped", 90, 30, 0, map == "MAP02" ? 2 : 0);
  }
  const nlohmann::json report{{"schema", "bspbench-report"}, {"version", kReportVersion},
                              {"suite", {{"name", "doom"}, {"definition_hash", "0"}, {"jobs", runs.size()}}},
                              {"shards", {{{"index", 0}, {"count", 1}, {"jobs", runs.size()}}}},
                              {"summary", nlohmann::json::object()}, {"aggregates", nlohmann::json::array()},
                              {"runs", runs}, {"failures", nlohmann::json::array()}};
  std::ofstream(dir_ / "made.json") << report.dump();
  ASSERT_EQ(bspbench("report --in made.json --out html"), 0) << err_;
  const std::string page = slurp(dir_ / "html" / "index.html");
  for (const char* expected : {"Paterson–Yao bound", "Every size stays under the bound", "Doom maps: our heuristics",
                               "doom-depth: target met", "doom-splits: target not judged",
                               "doom-search: target not judged", "CPU time at most 10× ZDBSP",
                               "<code>bspbench sweep --suite doom --out made.json</code>"})
    EXPECT_NE(page.find(expected), std::string::npos) << expected;
  const std::regex img("<img src='([^']+)'");
  std::size_t images = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), img); it != std::sregex_iterator(); ++it, ++images)
    EXPECT_TRUE(is_png(dir_ / "html" / (*it)[1].str())) << (*it)[1].str();
  EXPECT_EQ(images, 3u);  // the scoreboard, the bound plot, and the Doom Pareto plots (one image)
  EXPECT_EQ(page.find("{&quot;"), std::string::npos) << "a JSON dump in the page";
  EXPECT_NE(page.find("<h3>Environment</h3>"), std::string::npos);
}

// ---- Suites users write (suite/suite_file.h, analysis/SUITE_SCHEMA.md) ----

namespace {

const fs::path kExampleSuite = fs::path(BSPBENCH_SOURCE_DIR) / "examples" / "suites" / "example.json";
const fs::path kCourtyard = fs::path(BSPBENCH_SOURCE_DIR) / "examples" / "suites" / "meshes" / "courtyard.obj";

// Lines of `text` (a trailing newline ends the last one).
std::size_t line_count(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

// The committed example suite: (city at 2 sizes + the courtyard mesh) x 2 heuristics x 2 shapes x 3
// seeds = 36 runs, none failing; one and two threads agree in every deterministic field; the report
// records the suite file's text; the mesh is a scene of the report like a generated one; a mesh
// run's command rebuilds its tree.
TEST_F(SweepCli, ExampleSuiteFileRunsAlikeOnOneAndTwoThreadsAndItsReportRenders) {
  ASSERT_EQ(bspbench("sweep --suite " + kExampleSuite.string() + " --threads 1 --out one/report.json"), 0) << err_;
  ASSERT_EQ(bspbench("sweep --suite " + kExampleSuite.string() + " --threads 2 --out two/report.json"), 0) << err_;
  const auto one = read_report((dir_ / "one" / "report.json").string());
  const auto two = read_report((dir_ / "two" / "report.json").string());
  EXPECT_EQ(one["runs"].size(), 36u);
  EXPECT_EQ(one["summary"]["failures"], 0);
  EXPECT_EQ(one["summary"]["complete"], true);
  EXPECT_EQ(one["summary"]["invariant_violations"], 0);
  EXPECT_EQ(one["summary"]["validation_violations"], 0);
  EXPECT_TRUE(deterministic_view(one) == deterministic_view(two)) << "1 and 2 threads differ";
  EXPECT_EQ(one["suite"]["name"], "example");
  EXPECT_EQ(one["suite"]["source"]["path"], kExampleSuite.string());
  EXPECT_EQ(one["suite"]["source"]["text"], slurp(kExampleSuite));

  std::map<std::string, std::size_t> per_scene;
  const nlohmann::json* mesh_run = nullptr;
  for (const auto& r : one["runs"]) {
    const auto& id = r["id"];
    ++per_scene[id["scene"].get<std::string>()];
    if (id["scene"] == "file:meshes/courtyard.obj") {
      EXPECT_EQ(id["n"], 0);
      EXPECT_EQ(id["n_polygons"], 59);
      EXPECT_TRUE(id["scene_params"].empty());
      EXPECT_TRUE(id.contains("scene_file_hash"));
      if (id["seed"] == 2 && id["shape"] == "strict") mesh_run = &r;
    } else {
      EXPECT_EQ(id["scene_params"]["max_height"], 12.0) << id;  // the generator's parameter reached the scene
    }
  }
  EXPECT_EQ(per_scene, (std::map<std::string, std::size_t>{{"city", 24}, {"file:meshes/courtyard.obj", 12}}));

  ASSERT_NE(mesh_run, nullptr);
  const std::string command = (*mesh_run)["id"]["command"];
  ASSERT_EQ(command.rfind("bspbench build --input ", 0), 0u) << command;
  ASSERT_EQ(bspbench(command.substr(9) + " --json"), 0) << command << "\n" << err_;
  const auto rebuilt = nlohmann::json::parse(out_);
  for (const char* metric : {"fragments", "max_depth", "e_point", "e_line"})
    EXPECT_EQ(rebuilt[metric], (*mesh_run)["metrics"][metric]) << metric << " of " << command;

  ASSERT_EQ(bspbench("report --in one/report.json --out html"), 0) << err_;
  const std::string page = slurp(dir_ / "html" / "index.html");
  EXPECT_NE(page.find("<h2 id='city'>city</h2>"), std::string::npos);
  EXPECT_NE(page.find(">file:meshes/courtyard.obj</h2>"), std::string::npos);
  const std::regex img("<img src='([^']+)'");
  std::set<std::string> images;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), img); it != std::sregex_iterator(); ++it) {
    images.insert((*it)[1].str());
    EXPECT_TRUE(is_png(dir_ / "html" / (*it)[1].str())) << (*it)[1].str();
  }
  // A Pareto view and a scaling plot per scene, the mesh's like the generator's.
  for (const char* png : {"pareto-city.png", "scaling-city.png", "pareto-file_meshes_courtyard.obj.png",
                          "scaling-file_meshes_courtyard.obj.png"})
    EXPECT_TRUE(images.count(png)) << png;
}

// A suite file's journal is keyed by its text: the same file resumes, an edited one (even its
// summary alone) starts afresh; an edited mesh changes exactly its runs' keys. Shards of a suite
// file merge to the unsharded report.
TEST_F(SweepCli, SuiteFileJournalFollowsItsTextAndItsMeshAndShardsMerge) {
  fs::create_directories(dir_ / "suite" / "meshes");
  fs::copy_file(kCourtyard, dir_ / "suite" / "meshes" / "courtyard.obj");
  const auto write_suite = [&](const std::string& summary) {
    std::ofstream(dir_ / "suite" / "mine.json")
        << R"({"name": "mine", "summary": ")" << summary << R"(", "blocks": [{"scenes": ["city", "file:meshes/courtyard.obj"],
             "heuristics": ["crystal"], "sizes": [96], "seeds": [1, 2], "validation": {"views": 1}}]})";
  };
  const auto keys = [&](const std::string& report) {
    std::map<std::string, std::string> out;  // key -> scene
    const auto read = read_report((dir_ / report).string());
    for (const auto& r : read["runs"]) out[r["key"].get<std::string>()] = r["id"]["scene"].get<std::string>();
    return out;
  };
  write_suite("first");
  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 2 --out a.json --journal-dir j"), 0) << err_;
  EXPECT_NE(err_.find("4 jobs, 0 already in"), std::string::npos) << err_;
  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 2 --out b.json --journal-dir j"), 0) << err_;
  EXPECT_NE(err_.find("4 jobs, 4 already in"), std::string::npos) << err_;
  write_suite("second");
  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 2 --out c.json --journal-dir j"), 0) << err_;
  EXPECT_NE(err_.find("4 jobs, 0 already in"), std::string::npos) << err_;
  EXPECT_NE(read_report((dir_ / "a.json").string())["suite"]["definition_hash"],
            read_report((dir_ / "c.json").string())["suite"]["definition_hash"]);
  EXPECT_EQ(keys("a.json").size(), 4u);
  EXPECT_EQ(keys("a.json"), keys("c.json"));  // the same runs

  std::ofstream(dir_ / "suite" / "meshes" / "courtyard.obj", std::ios::app) << "# edited\n";
  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 2 --out d.json --journal-dir j"), 0) << err_;
  const auto before = keys("c.json"), after = keys("d.json");
  ASSERT_EQ(after.size(), 4u);
  for (const auto& [key, scene] : after) EXPECT_EQ(before.count(key), scene == "city" ? 1u : 0u) << scene;

  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 1 --shard 0/2 --out s0.json --journal-dir j"), 0) << err_;
  ASSERT_EQ(bspbench("sweep --suite suite/mine.json --threads 1 --shard 1/2 --out s1.json --journal-dir j"), 0) << err_;
  ASSERT_EQ(bspbench("merge-reports --out merged.json s0.json s1.json"), 0) << err_;
  EXPECT_TRUE(deterministic_view(read_report((dir_ / "merged.json").string())) ==
              deterministic_view(read_report((dir_ / "d.json").string())));
}

// Every kind of bad suite file is exit code 2 and one line naming the file and the JSON path of the
// problem, and nothing is written: no report, no journal.
TEST_F(SweepCli, BadSuiteFilesAreOneLineErrorsWithTheirJsonPath) {
  fs::copy_file(kCourtyard, dir_ / "courtyard.obj");
  std::ofstream(dir_ / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  const std::string ok_block = R"("scenes": ["city"], "sizes": [100])";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "seedz": [1]}]})",
       "s.json: blocks[0]: unknown key 'seedz' (known: scenes, heuristics, incremental, sizes, scene_sizes, seeds, "
       "shapes, validation, kernels)"},
      {R"({"name": "x", "bloks": []})", "s.json: unknown key 'bloks'"},
      {R"({"name": "x", "blocks": [{"scenes": ["city"], "sizes": "100"}]})",
       "s.json: blocks[0].sizes: expected an array, got string"},
      {R"({"name": 7, "blocks": [{)" + ok_block + "}]}", "s.json: name: expected a string, got 7"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": ["crystal", "foo"]}]})",
       "s.json: blocks[0].heuristics[1]: unknown heuristic 'foo' (known: "},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": [{"name": "weighted", "params": {"splits": 1}}]}]})",
       "s.json: blocks[0].heuristics[0].params.splits: heuristic weighted: unknown parameter 'splits' (known: "},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": ["crystal:splits=1"]}]})",
       "s.json: blocks[0].heuristics[0]: heuristic crystal: unknown parameter 'splits'"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": ["weighted:candidates=-3"]}]})",
       "s.json: blocks[0].heuristics[0]: heuristic weighted: parameter candidates=-3 is outside [0, "},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": [{"name": "naylor", "params": {"model": 3}}]}]})",
       "s.json: blocks[0].heuristics[0].params.model: expected a string (one of the parameter's choices), got 3"},
      {R"({"name": "x", "blocks": [{"scenes": ["citty"], "sizes": [100]}]})",
       "s.json: blocks[0].scenes[0]: unknown scene 'citty' (known: "},
      {R"({"name": "x", "blocks": [{"scenes": [{"generator": "city", "params": {"max_height": 0}}], "sizes": [100]}]})",
       "s.json: blocks[0].scenes[0].params.max_height: scene city: parameter max_height=0 is outside ["},
      {R"({"name": "x", "blocks": [{"scenes": [{"generator": "city", "params": {"n": 100}}], "sizes": [100]}]})",
       "s.json: blocks[0].scenes[0].params.n: a scene's size comes from \"sizes\""},
      {R"({"name": "x", "blocks": [{"scenes": ["city", "file:missing.obj"], "sizes": [100]}]})",
       "s.json: blocks[0].scenes[1]: no such file: "},
      {R"({"name": "x", "blocks": [{"scenes": ["file:broken.obj"]}]})", "s.json: blocks[0].scenes[0]: "},
      {R"({"name": "x", "blocks": [{"scenes": ["mesh:no-such-mesh"]}]})",
       "s.json: blocks[0].scenes[0]: unknown mesh scene 'mesh:no-such-mesh'"},
      {"{\"name\": \"x\",\n \"blocks\": [{\"scenes\": [\"city\"],}]}",
       "s.json: malformed JSON at line 2, column 33: syntax error"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "seeds": []}]})",
       "s.json: blocks[0].seeds: empty list (give at least one seed)"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "seeds": [1, 2, 1]}]})",
       "s.json: blocks[0].seeds[2]: repeats blocks[0].seeds[0]"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "heuristics": ["crystal", "crystal:candidates=20"]}]})",
       "s.json: blocks[0].heuristics[1]: repeats blocks[0].heuristics[0]"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "sizes": [200]}]})", "s.json: blocks[0]: key 'sizes' given twice"},
      {R"({"name": "x", "blocks": [{"scenes": ["city"], "sizes": [1000000000]}]})",
       "s.json: blocks[0].sizes[0]: 1000000000 is outside city's range of n, [1, 1e+08]"},
      {R"({"name": "x", "blocks": [{"scenes": ["city"]}]})", "s.json: blocks[0]: missing key 'sizes' (city takes a size n)"},
      {R"({"name": "x", "blocks": [{"scenes": ["file:courtyard.obj"], "sizes": [100]}]})",
       "s.json: blocks[0].sizes: no scene of this block takes a size"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "incremental": true, "shapes": ["leafy"]}]})",
       "s.json: blocks[0].shapes[0]: a leafy tree is built recursively, not incrementally"},
      {R"({"name": "x", "blocks": [{)" + ok_block + R"(, "shapes": ["round"]}]})",
       "s.json: blocks[0].shapes[0]: unknown shape 'round' (known: strict, coarse, leafy)"},
      {R"({"name": "x", "animations": [{}]})", "s.json: animations[0]: missing key 'scenes'"},
      {R"({"name": "x", "animations": [{"scenes": ["city"], "sizes": [100], "moving": [2], "speeds": [0.01], "strategies": ["teleport"]}]})",
       "s.json: animations[0].strategies[0]: unknown update strategy 'teleport' (known: "},
      {R"({"name": "x", "animations": [{"scenes": ["city"], "sizes": [100], "moving": [2], "speeds": [2]}]})",
       "s.json: animations[0].speeds[0]: 2 is more than 1"},
      {R"({"name": "x", "animations": [{"scenes": ["city"], "sizes": [100], "moving": [2], "speeds": [0.01], "object": "city"}]})",
       "s.json: animations[0].object: 'city' is not a closed solid"},
      {R"({"name": "x", "doom": [{"iwads": ["freedoom2.wad"], "builders": ["zenbsp"]}]})",
       "s.json: doom[0].builders[0]: unknown node builder 'zenbsp' (known: "},
      {R"({"name": "x", "doom": [{"iwads": ["../freedoom2.wad"]}]})",
       "s.json: doom[0].iwads[0]: '../freedoom2.wad' is not a file name in the Doom data directory"},
      {R"({"name": "x", "doom": [{"iwads": ["freedoom2.wad"], "heuristics": ["doom-splits", "doom-splits"]}]})",
       "s.json: doom[0].heuristics[1]: repeats doom[0].heuristics[0]"},
      {R"({"name": "quick", "blocks": [{)" + ok_block + "}]}", "s.json: name: 'quick' is a built-in suite"},
      {R"({"name": "x"})", "s.json: no runs: give \"blocks\", \"merges\", \"animations\", \"occlusions\", \"doom\", \"kernels\", \"csg\" or \"optimals\""},
      {R"({"name": "x", "merges": [{"pairs": ["spheres"], "ops": ["unite"], "sizes": [50]}]})",
       "s.json: merges[0].ops[0]: unknown set operation 'unite'"},
      {R"({"name": "x", "occlusions": [{"scenes": ["random-segments"], "sizes": [100]}]})",
       "s.json: occlusions[0].scenes[0]: random-segments is 2D"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [text, message] = cases[i];
    std::ofstream(dir_ / "s.json") << text;
    EXPECT_EQ(bspbench("sweep --suite s.json --out out/report.json"), 2) << text << "\n" << err_;
    EXPECT_EQ(err_.rfind("bspbench sweep: " + message, 0), 0u) << "case " << i << ": " << err_;
    EXPECT_EQ(line_count(err_), 1u) << "case " << i << ": " << err_;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << "case " << i << " wrote output";
  }
  // The broken mesh is named with its own problem after the JSON path.
  std::ofstream(dir_ / "s.json") << R"({"name": "x", "blocks": [{"scenes": ["file:broken.obj"]}]})";
  EXPECT_EQ(bspbench("sweep --suite s.json --out out/report.json"), 2);
  EXPECT_NE(err_.find("s.json: blocks[0].scenes[0]: broken.obj: "), std::string::npos) << err_;
  EXPECT_EQ(bspbench("sweep --suite nowhere/s.json --out out/report.json"), 2);
  EXPECT_EQ(err_, "bspbench sweep: nowhere/s.json: no such suite file\n");
}

// A suite file takes every kind of block, as the built-in suites (which are such files) do: an
// animation and a Doom map run from one file, proved, with the commands that repeat them; a map the
// IWAD lacks stops the sweep before any job runs.
TEST_F(SweepCli, SuiteFileRunsAnimationAndDoomBlocks) {
  if (!fs::exists("/usr/share/games/doom/freedoom2.wad") && !std::getenv("BSPBENCH_DOOM_DIR"))
    GTEST_SKIP() << "needs the Freedoom IWADs (apt-get install freedoom)";
  std::ofstream(dir_ / "s.json") << R"({"name": "kinds",
    "animations": [{"scenes": ["city"], "sizes": [100], "heuristics": ["crystal"], "strategies": ["rebuild"],
                    "moving": [1], "speeds": [0.01], "frames": 3, "object_n": 24, "check_every": 1, "views": 1}],
    "doom": [{"iwads": ["freedoom2.wad"], "maps": ["MAP01"], "heuristics": ["crystal"], "views": 1}]})";
  ASSERT_EQ(bspbench("sweep --suite s.json --out r.json"), 0) << err_;
  const auto report = read_report((dir_ / "r.json").string());
  std::map<std::string, int> kinds;
  for (const auto& r : report["runs"]) {
    ++kinds[r["id"]["kind"].get<std::string>()];
    EXPECT_EQ(r["invariants"]["violations"], 0) << r["id"]["command"];
  }
  EXPECT_EQ(kinds, (std::map<std::string, int>{{"animate", 1}, {"doom", 2}}));  // ours and the shipped nodes
  EXPECT_EQ(report["suite"]["source"]["path"], "s.json");
  std::ofstream(dir_ / "s.json") << R"({"name": "kinds", "doom": [{"iwads": ["freedoom2.wad"], "maps": ["MAP99"]}]})";
  EXPECT_EQ(bspbench("sweep --suite s.json --out bad/r.json"), 2);
  EXPECT_NE(err_.find("freedoom2.wad: no map MAP99"), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

// A mesh of the cache, mesh:NAME, runs once per heuristic and seed under that name.
TEST_F(SweepCli, SuiteFileRunsACachedMeshByName) {
  const auto meshes = bsp::available_meshes();
  if (std::none_of(meshes.begin(), meshes.end(), [](const bsp::MeshEntry& m) { return m.name == "P"; }))
    GTEST_SKIP() << "no sample meshes (generators/fetch_meshes.sh)";
  std::ofstream(dir_ / "s.json")
      << R"({"name": "cached", "blocks": [{"scenes": ["mesh:P"], "heuristics": ["crystal", "naylor"], "seeds": [1, 2]}]})";
  ASSERT_EQ(bspbench("sweep --suite s.json --threads 2 --out r.json"), 0) << err_;
  const auto report = read_report((dir_ / "r.json").string());
  ASSERT_EQ(report["runs"].size(), 4u);
  for (const auto& r : report["runs"]) {
    EXPECT_EQ(r["id"]["scene"], "mesh:P");
    EXPECT_EQ(r["id"]["command"].get<std::string>().rfind("bspbench build --scene mesh:P --seed ", 0), 0u) << r["id"];
    EXPECT_EQ(r["invariants"]["violations"], 0);
  }
}
