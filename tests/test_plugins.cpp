// Plugins through the real binary (experiments/plugin_loader.h): a plugin's heuristic runs like a
// built-in's, its identity joins job keys and commands, and every bad plugin is one line on stderr
// with exit code 2 (the plugin's fault found when loading) or 3 (its code threw), nothing written.
// The plugins are tests/plugins/*.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace fs = std::filesystem;

namespace {

using bsp::testing::CliResult;

class Plugins : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = bsp::testing::fresh_test_dir("bspbench_plugins");
    fs::create_directories(dir_ / "out");
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string plugin(const std::string& name) { return std::string(BSPBENCH_TEST_PLUGIN_DIR) + "/" + name + ".so"; }
  CliResult run(const std::string& args) const { return bsp::testing::run_bspbench(args, dir_); }

  // Exit `code`, one error line on stderr holding each of `words` (the only line, or for a sweep
  // the only one after its progress notes), nothing on stdout or in out/.
  void expect_one_line(const CliResult& r, int code, std::initializer_list<std::string> words) const {
    EXPECT_EQ(r.code, code) << r.err;
    const bool sweep = r.err.find("bspbench sweep:") != std::string::npos;
    EXPECT_EQ(sweep ? count_of(r.err, "bspbench ") : std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
    for (const auto& w : words) EXPECT_NE(last.find(w), std::string::npos) << "no '" << w << "' in: " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "output written despite the error";
  }

  static std::ptrdiff_t count_of(const std::string& text, const std::string& word) {
    std::ptrdiff_t n = 0;
    for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
    return n;
  }

  fs::path write_suite(const std::string& heuristics, const std::string& plugins) const {
    const fs::path p = dir_ / "suite.json";
    std::ofstream(p) << R"({"name": "plugin-test", )" << plugins
                     << R"("blocks": [{"scenes": ["random-triangles"], "sizes": [60], "heuristics": )" << heuristics
                     << R"(, "validation": {"views": 1}}]})";
    return p;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(Plugins, HeuristicBuildsAndIsListedLikeABuiltIn) {
  const CliResult listed = run("heuristics --plugin " + plugin("good"));
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_NE(listed.out.find("test_first_plugin"), std::string::npos) << listed.out;
  // The plugin's `first` and the built-in `first` build the same tree.
  const std::string scene = " --scene random-triangles --n 300 --views 2 --json";
  const CliResult ours = run("build --plugin=" + plugin("good") + " --heuristic test_first_plugin" + scene);
  const CliResult builtin = run("build --heuristic first" + scene);
  ASSERT_EQ(ours.code, 0) << ours.err;
  ASSERT_EQ(builtin.code, 0) << builtin.err;
  auto a = nlohmann::json::parse(ours.out), b = nlohmann::json::parse(builtin.out);
  for (const char* k : {"nodes", "depth_max", "fragments", "splits"}) EXPECT_EQ(a[k], b[k]) << k;
}

TEST_F(Plugins, SweepKeysAndCommandsCarryThePlugin) {
  const fs::path suite = write_suite(R"(["test_first_plugin", "first"])", "");
  const fs::path out = dir_ / "report.json";
  const CliResult r = run("sweep --plugin " + plugin("good") + " --suite " + suite.string() + " --fresh --threads 1 --out " +
                          out.string() + " --journal-dir " + (dir_ / "journal").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(bsp::testing::slurp(out));
  const auto& env = report["shards"][0]["environment"];
  ASSERT_EQ(env["plugins"].size(), 1u) << env.dump();
  EXPECT_EQ(env["plugins"][0]["name"], "test_plugin");
  EXPECT_EQ(env["plugins"][0]["version"], "0.0.1");
  std::string plugin_key, builtin_key;
  for (const auto& run : report["runs"]) {
    const std::string command = run["id"]["command"];
    const bool ours = run["id"]["heuristic"] == "test_first_plugin";
    EXPECT_EQ(command.find("--plugin " + plugin("good")) != std::string::npos, ours) << command;
    (ours ? plugin_key : builtin_key) = run["key"];
  }
  ASSERT_FALSE(plugin_key.empty());
  // Another build of the plugin (the same code with a byte more) is another plugin: another key.
  // The built-in's key does not depend on the plugins loaded.
  const fs::path copy = dir_ / "good_copy.so";
  fs::copy_file(plugin("good"), copy);
  std::ofstream(copy, std::ios::app | std::ios::binary) << '\0';
  const fs::path out2 = dir_ / "report2.json";
  const CliResult r2 = run("sweep --plugin " + copy.string() + " --suite " + suite.string() + " --fresh --threads 1 --out " +
                           out2.string() + " --journal-dir " + (dir_ / "journal").string());
  ASSERT_EQ(r2.code, 0) << r2.err;
  const auto report2 = nlohmann::json::parse(bsp::testing::slurp(out2));
  ASSERT_EQ(report2["runs"].size(), 2u);
  for (const auto& run : report2["runs"]) {
    if (run["id"]["heuristic"] == "test_first_plugin") EXPECT_NE(run["key"], plugin_key);
    else EXPECT_EQ(run["key"], builtin_key);
  }
}

TEST_F(Plugins, SuiteFileLoadsItsPlugins) {
  fs::copy_file(plugin("good"), dir_ / "good.so");
  const fs::path suite = write_suite(R"(["test_first_plugin"])", R"("plugins": ["good.so"], )");
  const fs::path out = dir_ / "report.json";
  const CliResult r = run("sweep --suite " + suite.string() + " --fresh --threads 1 --out " + out.string() +
                          " --journal-dir " + (dir_ / "journal").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(bsp::testing::slurp(out))["runs"].size(), 1u);
  // A suite naming a plugin that is not there: one line naming the suite's key.
  const fs::path bad = write_suite(R"(["test_first_plugin"])", R"("plugins": ["missing.so"], )");
  expect_one_line(run("sweep --suite " + bad.string() + " --out " + (dir_ / "out" / "r.json").string()), 2,
                  {"plugins[0]", "missing.so", "no such file"});
}

TEST_F(Plugins, BadPluginsAreOneLineExitTwo) {
  const std::string build = " --scene random-triangles --n 50 --heuristic first";
  expect_one_line(run("build --plugin " + plugin("other_version") + build), 2,
                  {"other_version.so", "built for", "bspbench 0.0", "rebuild the plugin"});
  expect_one_line(run("build --plugin " + plugin("no_entry") + build), 2, {"no_entry.so", "not a bspbench plugin"});
  expect_one_line(run("build --plugin " + plugin("duplicate") + build), 2, {"duplicate.so", "'naylor'", "already registered"});
  expect_one_line(run("build --plugin " + (dir_ / "nothing.so").string() + build), 2, {"nothing.so", "no such file"});
  const fs::path garbage = dir_ / "garbage.so";
  std::ofstream(garbage) << "not an ELF file";
  expect_one_line(run("build --plugin " + garbage.string() + build), 2, {"garbage.so", "cannot load"});
  // The same good plugin twice is loaded once, not a duplicate.
  EXPECT_EQ(run("build --plugin " + plugin("good") + " --plugin " + plugin("good") + build).code, 0);
}

TEST_F(Plugins, ExceptionInPluginCodeIsOneLineExitThree) {
  expect_one_line(run("heuristics --plugin " + plugin("describe_throws")), 3,
                  {"describe_throws.so", "describe failed on purpose"});
  // Thrown deep in a build of two threads, inside the build's parallel tasks.
  expect_one_line(run("build --plugin " + plugin("good") +
                      " --scene random-triangles --n 4000 --heuristic test_throws --param depth=14"),
                  3, {"plugin test_plugin", "heuristic test_throws", "choose() threw", "deep enough"});
  expect_one_line(run("build --plugin " + plugin("good") + " --scene random-triangles --n 50 --heuristic test_outside"), 3,
                  {"heuristic test_outside", "not in the node"});
  expect_one_line(run("build --plugin " + plugin("good") + " --scene random-triangles --n 50 --heuristic test_free_autopartition"),
                  3, {"heuristic test_free_autopartition", "declared an autopartition"});
  // In a sweep: it stops, exit 3, no report.
  const fs::path suite = write_suite(R"(["test_throws", "first"])", "");
  expect_one_line(run("sweep --plugin " + plugin("good") + " --suite " + suite.string() + " --fresh --threads 2 --out " +
                      (dir_ / "out" / "report.json").string() + " --journal-dir " + (dir_ / "journal").string()),
                  3, {"choose() threw"});
}
