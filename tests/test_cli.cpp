// The real bspbench binary on bad input: every bad file gives exit code 2, one
// line on stderr naming the file and the problem, and no output files; every bad command line gives
// exit code 2 and the usage line.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace fs = std::filesystem;

namespace {

using bsp::testing::CliResult;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = bsp::testing::fresh_test_dir("bspbench_cli");
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& content) const {
    const fs::path p = dir_ / name;
    std::ofstream(p) << content;
    return p;
  }

  CliResult run(const std::string& args) const { return bsp::testing::run_bspbench(args, dir_); }

  // `order` and `validate` on a bad input file: exit 2, one stderr line naming the file and
  // containing `problem`, nothing written.
  void expect_input_error(const fs::path& file, const std::string& problem) const {
    for (const std::string command : {"validate", "order", "compare"}) {
      SCOPED_TRACE(command + " " + file.string());
      const std::string out = command == "order" ? " --eye 0.5,0.5,4 --out " + (dir_ / "out" / "run").string() : "";
      const std::string heuristic = command == "compare" ? " --heuristics first" : " --heuristic first";
      const CliResult r = run(command + " --input " + file.string() + heuristic + out);
      EXPECT_EQ(r.code, 2);
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
      EXPECT_TRUE(r.out.empty()) << r.out;
      EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "partial output left behind";
    }
  }

  // A bad command line: exit 2, the usage line, no output.
  void expect_usage_error(const std::string& args, const std::string& problem) const {
    SCOPED_TRACE(args);
    const CliResult r = run(args);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find(problem), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("usage: bspbench"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "output written despite a usage error";
  }

  fs::path dir_;
};

}  // namespace

// A user's mesh through compare: read once, every seed feeding only the heuristics, each checked.
TEST_F(Cli, CompareTakesAMeshFileAndRunsEverySeedOnIt) {
  const fs::path mesh = write("box.obj",
                              "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                              "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
                              "v 0.2 0.2 0.5\nv 0.8 0.3 0.5\nv 0.5 0.9 0.6\nf 9 10 11\n");
  const CliResult r = run("compare --input " + mesh.string() + " --heuristics first,crystal --seeds 3 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scene"], mesh.string());
  ASSERT_EQ(j["scenes"].size(), 1u) << "a file is one scene whatever the seed";
  EXPECT_TRUE(j["scenes"][0]["seed"].is_null());
  ASSERT_EQ(j["heuristics"].size(), 2u);
  for (const auto& h : j["heuristics"]) {
    EXPECT_EQ(h["runs"].size(), 3u);
    EXPECT_EQ(h["validation"]["failures"], 0u);
    EXPECT_EQ(h["metrics"]["n_input"]["mean"], 7.0);
  }
  expect_usage_error("compare --input " + mesh.string() + " --n 10 --heuristics first", "--input");
  expect_usage_error("compare --input " + mesh.string() + " --scene city --heuristics first", "either --scene");
}

TEST_F(Cli, MissingFileIsNamed) { expect_input_error(dir_ / "missing.obj", "no such file"); }

TEST_F(Cli, UnreadableFileIsNamed) {
  // A mode-000 file is readable for root, who runs the README's commands, so the unreadable file
  // is /proc/sys/vm/drop_caches, through a link with a mesh extension: it exists and is a regular
  // file, but as a write-only sysctl its mode bits bind root too (the kernel's sysctl permission
  // check grants no override), so open() fails with EACCES for everyone.
  const fs::path p = dir_ / "locked.obj";
  fs::create_symlink("/proc/sys/vm/drop_caches", p);
  ASSERT_TRUE(fs::is_regular_file(p));
  ASSERT_FALSE(std::ifstream(p).good()) << "expected open() to fail on " << p << " even for root";
  expect_input_error(p, "cannot open (Permission denied)");
}

TEST_F(Cli, DirectoryAndUnknownExtensionAreNamed) {
  fs::create_directories(dir_ / "folder.obj");
  expect_input_error(dir_ / "folder.obj", "is a directory");
  expect_input_error(write("mesh.txt", "v 0 0 0\n"), "unsupported file type");
}

TEST_F(Cli, MalformedMeshIsNamed) {
  expect_input_error(write("garbage.obj", "this is not a mesh\nv 1 2\nf 1 2 3 4 5\n"), "malformed");
  expect_input_error(write("truncated.off", "OFF\n3 1 0\n1 2\n"),
                     "header claims 3 vertices and 1 faces but the file has only 14 bytes");
}

TEST_F(Cli, NonFiniteCoordinatesAreRejected) {
  // CGAL's reader refuses the tokens nan, inf and 1e400 without a reason; the reader then names
  // the line with the non-finite number.
  for (const std::string value : {"nan", "inf", "1e400"}) {
    expect_input_error(write("bad_" + value + ".off", "OFF\n3 1 0\n0 0 0\n1 0 0\n" + value + " 1 0\n3 0 1 2\n"),
                       "line 5 has a non-finite (NaN or infinite) coordinate");
    expect_input_error(write("bad_" + value + ".obj", "v 0 0 0\nv 1 0 0\nv " + value + " 1 0\nf 1 2 3\n"),
                       "line 3 has a non-finite (NaN or infinite) coordinate");
  }
}

TEST_F(Cli, EmptySceneIsNamed) {
  expect_input_error(write("no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), "no polygons");
  expect_input_error(write("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), "no polygons");
  expect_input_error(write("vertices_only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "the file has no faces");
}

TEST_F(Cli, BadArgumentsPrintTheUsageLine) {
  const std::string scene = "--scene random-triangles --n 50";
  const std::string out = " --out " + (dir_ / "out" / "run").string();
  expect_usage_error("validate " + scene + " --heuristic first --bogus 1", "unexpected argument '--bogus'");
  expect_usage_error("validate " + scene, "missing option --heuristic");
  expect_usage_error("validate " + scene + " --heuristic no-such-heuristic", "unknown heuristic");
  expect_usage_error("validate --scene random-triangles --n abc --heuristic first", "abc");
  expect_usage_error("validate --scene random-triangles --n 0 --heuristic first", "outside");
  expect_usage_error("validate " + scene + " --heuristic first --views 0", "--views");
  expect_usage_error("order " + scene + " --heuristic first --eye 1,2" + out, "--eye");
  expect_usage_error("order " + scene + " --heuristic first --eye 1,2,nan" + out, "--eye");
  expect_usage_error("order " + scene + " --heuristic first --eye 1,2,3", "missing option --out");
  expect_usage_error("order " + scene + " --heuristic nope --eye 1,2,3" + out, "unknown heuristic");
  expect_usage_error("build " + scene + " --heuristic first --kernel double", "--kernel must be float or exact");
  expect_usage_error("validate " + scene + " --heuristic first --shape leafy --kernel exact", "--kernel exact builds");
  expect_usage_error("build " + scene + " --incremental --kernel exact", "--kernel exact builds");
}

// The exact kernel on the commands that take it: its key joins the JSON (only when not float), with
// what snapping and the predicates did, and its orders and validation come out whole.
TEST_F(Cli, ExactKernelRunsBuildOrderAndValidate) {
  const std::string scene = "--scene near-degenerate --n 200 --heuristic crystal";
  const CliResult b = run("build " + scene + " --kernel exact --views 1 --rays 50 --json");
  ASSERT_EQ(b.code, 0) << b.err;
  const auto built = nlohmann::json::parse(b.out);
  EXPECT_EQ(built["kernel"], "exact");
  EXPECT_EQ(built["dropped_slivers"], 0);
  EXPECT_GT(built["exact"]["predicates"]["filtered"].get<std::uint64_t>(), 0u);
  EXPECT_FALSE(nlohmann::json::parse(run("build " + scene + " --views 1 --rays 50 --json").out).contains("kernel"));
  const CliResult v = run("validate " + scene + " --kernel exact --views 2 --json");
  ASSERT_EQ(v.code, 0) << v.err;
  const auto validated = nlohmann::json::parse(v.out);
  EXPECT_EQ(validated["violations"], 0);
  EXPECT_EQ(validated["ties"], 0);
  const std::string prefix = (dir_ / "out" / "exact").string();
  const CliResult o = run("order " + scene + " --kernel exact --eye 1,2,3 --out " + prefix);
  ASSERT_EQ(o.code, 0) << o.err;
  std::ifstream in(prefix + ".order.json");
  const auto order = nlohmann::json::parse(in);
  EXPECT_EQ(order["back_to_front"].size(), order["fragments"].get<std::size_t>());
  EXPECT_EQ(order["eye_snapped"].size(), 3u);
}

TEST_F(Cli, ValidatePrintsOneJsonObjectWithTheCounts) {
  const CliResult r = run("validate --scene cyclic-overlap --n 60 --heuristic first --views 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
  for (const char* key : {"\"rays\":", "\"pairs_checked\":", "\"violations\":0", "\"rays_per_second\":", "\"heuristic\":"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
}

// The optimum of a small 2D scene, proved, its tree checked, and a gap for each heuristic named; a
// budget that runs out gives an interval; what the solver cannot take is refused.
TEST_F(Cli, OptimalProvesTheOptimumAndGivesEachHeuristicsGap) {
  const CliResult r = run("optimal --scene random-segments --n 12 --heuristic first --heuristic halving --views 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out)["optimum"];
  EXPECT_TRUE(out["optimal"].get<bool>());
  EXPECT_EQ(out["lower"], out["upper"]);
  EXPECT_EQ(out["certificate_value"], out["upper"]);
  EXPECT_EQ(out["order_violations"], 0);
  ASSERT_EQ(out["heuristics"].size(), 2u);
  EXPECT_GE(out["heuristics"][0]["gap_lower"].get<double>(), 1.0);
  EXPECT_FALSE(out["heuristics"][1]["autopartition"].get<bool>());
  const CliResult cut = run("optimal --scene random-triangles --n 24 --scene-param size=0.5 --max-states 50 "
                            "--objective e_line --heuristic first --views 1 --json");
  ASSERT_EQ(cut.code, 0) << cut.err;
  const auto bounded = nlohmann::json::parse(cut.out)["optimum"];
  EXPECT_FALSE(bounded["optimal"].get<bool>());
  EXPECT_LT(bounded["lower"].get<double>(), bounded["upper"].get<double>());
  EXPECT_TRUE(bounded["solver"]["out_of_states"].get<bool>());
  expect_usage_error("optimal --scene random-segments --n 12 --objective size", "--objective");
  expect_usage_error("optimal --scene random-triangles --n 400", "distinct planes");
}

TEST_F(Cli, AnimateChecksEveryFrameAndRefusesUnknownStrategies) {
  const CliResult r = run("animate --scene city --n 300 --moving 2 --frames 4 --object-n 24 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["summary"]["frames"], 4);
  EXPECT_EQ(out["summary"]["frames_checked"], 4);
  EXPECT_EQ(out["summary"]["order_violations"], 0);
  EXPECT_EQ(out["per_frame"].size(), 4u);
  EXPECT_EQ(out["animation"]["paths"].size(), 2u);
  expect_usage_error("animate --scene city --n 300 --frames 4 --strategy teleport", "unknown update strategy");
  expect_usage_error("animate --scene city --n 300 --object city", "not a closed solid");
}

TEST_F(Cli, AnimateRunsEveryStrategyWithDrift) {
  for (const std::string strategy : {"reinsert", "reinsert-each", "merge", "torres"}) {
    const CliResult r = run("animate --scene city --n 300 --moving 2 --frames 4 --object-n 24 --drift-every 2 --strategy " +
                            strategy + " --json");
    ASSERT_EQ(r.code, 0) << strategy << r.err;
    const auto out = nlohmann::json::parse(r.out);
    EXPECT_EQ(out["summary"]["invariant_violations"], 0);
    EXPECT_EQ(out["object_heuristic"], strategy == "torres" ? "halving" : "crystal");
    EXPECT_TRUE(out["per_frame"][2]["drift"].is_object());
    EXPECT_TRUE(out["per_frame"][1]["drift"].is_null());
    EXPECT_GT(out["summary"]["drift_last"]["fresh_fragments"].get<double>(), 0);
  }
  expect_usage_error("animate --scene city --n 300 --frames 4 --strategy merge --shape coarse", "strict tree");
  const std::string obj = (dir_ / "arch.obj").string();
  ASSERT_EQ(run("generate --scene architecture --n 120 --out " + obj).code, 0);
  const CliResult file = run("animate --input " + obj + " --moving 1 --frames 2 --object-n 24 --strategy reinsert --json");
  ASSERT_EQ(file.code, 0) << file.err;
  EXPECT_EQ(nlohmann::json::parse(file.out)["summary"]["invariant_violations"], 0);
  expect_usage_error("animate --input " + obj + " --n 5", "not --input");
  expect_usage_error("animate --input " + obj + " --scene city", "not both");
}

TEST_F(Cli, OccludeProvesEachViewAndRefusesBadEyes) {
  const CliResult r = run("occlude --scene architecture --n 300 --heuristic crystal --views 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  ASSERT_EQ(out["views"].size(), 2u);
  for (const auto& v : out["views"]) {
    EXPECT_EQ(v["missed_fragments"], 0);
    EXPECT_LE(v["emitted"].get<int>(), v["frustum_culled"].get<int>());
    EXPECT_GE(v["emitted"].get<int>(), v["seen_by_embree"].get<int>());
  }
  const CliResult one = run("occlude --scene architecture --n 300 --heuristic crystal --eye 30,20,10 --json");
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_EQ(nlohmann::json::parse(one.out)["views"].size(), 1u);
  expect_usage_error("occlude --scene architecture --n 300 --heuristic crystal --eye 1,2", "--eye");
  expect_usage_error("occlude --scene architecture --n 300 --heuristic crystal --look 1,0,0", "--look needs --eye");
  expect_usage_error("occlude --scene architecture --n 300 --heuristic crystal --eye 1,2,3 --fov 200", "--fov");
}

TEST_F(Cli, EveryJsonOutputCarriesTheScenesHashAndBoundingBox) {
  const std::string scene = "--scene city --n 60 --seed 4";
  const std::string out = (dir_ / "out" / "run").string();
  for (const std::string& command : std::vector<std::string>{
           "build " + scene + " --heuristic first", "validate " + scene + " --heuristic first --views 1",
           "order " + scene + " --heuristic first --eye 0,0,9 --out " + out, "generate " + scene + " --out " + out + ".obj",
           "compare " + scene + " --heuristics first --seeds 2 --views 1"}) {
    const CliResult r = run(command + " --json");
    ASSERT_EQ(r.code, 0) << command << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const std::string text = j.dump();
    EXPECT_NE(text.find("hash\":\""), std::string::npos) << command;
    EXPECT_NE(text.find("bounds\":{\"hi\""), std::string::npos) << command;
  }
}

// An incremental build consults no heuristic: naming one is a usage error, and the run is labelled
// "incremental", not with a heuristic that played no part.
TEST_F(Cli, IncrementalRefusesAHeuristicAndIsLabelledIncremental) {
  const std::string scene = "--scene random-triangles --n 50";
  expect_usage_error("build " + scene + " --incremental --heuristic naylor", "consults no heuristic");
  expect_usage_error("validate " + scene + " --incremental --heuristic first --views 1", "consults no heuristic");
  expect_usage_error("build " + scene + " --heuristic first --order shuffled", "--order applies to --incremental");
  const CliResult r = run("build " + scene + " --incremental --order shuffled --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["heuristic"], "incremental");
  EXPECT_EQ(j["build"], "incremental");
  EXPECT_EQ(j["heuristic_params"], nlohmann::json::object());
}

// `bspbench COMMAND --help` (and -h): the usage line and a meaning for every option the usage line
// names, exit 0, nothing on stderr.
TEST_F(Cli, EveryCommandsHelpExplainsEveryOptionOfItsUsageLine) {
  const std::vector<std::string> commands = {"build",        "compare", "heuristics", "scenes", "generate", "sweep",
                                             "merge-reports", "regress", "report",     "order",  "validate", "history"};
  const std::regex option("--[a-z][a-z-]*");
  for (const auto& name : commands) {
    for (const char* flag : {"--help", "-h"}) {
      SCOPED_TRACE(name + " " + flag);
      const CliResult r = run(name + " " + flag);
      EXPECT_EQ(r.code, 0);
      EXPECT_TRUE(r.err.empty()) << r.err;
      ASSERT_EQ(r.out.rfind("usage: bspbench " + name + " ", 0), 0u) << r.out;
      const std::string usage = r.out.substr(0, r.out.find('\n'));
      std::set<std::string> explained;
      std::istringstream lines(r.out.substr(r.out.find("options:") == std::string::npos ? r.out.size()
                                                                                         : r.out.find("options:")));
      for (std::string line; std::getline(lines, line);)
        if (line.rfind("  --", 0) == 0) explained.insert(line.substr(2, line.find_first_of(" \t", 2) - 2));
      for (auto it = std::sregex_iterator(usage.begin(), usage.end(), option); it != std::sregex_iterator(); ++it)
        EXPECT_TRUE(explained.count(it->str())) << it->str() << " has no meaning in\n" << r.out;
    }
  }
}

TEST_F(Cli, VersionNamesTheRevisionAndExitsZero) {
  const CliResult r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_TRUE(std::regex_match(r.out, std::regex("bspbench [0-9.]+ \\(revision ([0-9a-f]{12}(-dirty)?|unknown)\\)\n")))
      << r.out;
}
