// The sweep engine: suites take every registered heuristic and generator; the journal survives
// interruptions (torn last line, resume without rerunning); deterministic fields do not depend on
// the thread count; shards partition a suite and merge back, rejecting duplicate, missing and
// foreign shards; aggregates recover a known power law; the regression gate passes an identical
// report and fails a changed fragment count, a 3x faster or slower timing, a missing run and a
// violation, while a uniformly slower machine passes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "catalog.h"
#include "common/errors.h"
#include "split/registry.h"
#include "sweep/aggregate.h"
#include "sweep/journal.h"
#include "sweep/merge.h"
#include "sweep/progress.h"
#include "sweep/record.h"
#include "sweep/regress.h"
#include "sweep/report.h"
#include "sweep/runner.h"

using namespace bsp;
using namespace bsp::sweep;
namespace fs = std::filesystem;

namespace {

// 16 small jobs: enough for two sizes, two seeds and two of everything else, in a second or two.
Suite tiny_suite() {
  return {"tiny", "test suite",
          {{{"random-triangles", "cyclic-overlap"}, {"first", "random"}, {40, 80}, {}, {1, 2}, {Shape::Strict}, {1, 0, 1}}}};
}

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("bspbench_sweep_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                        std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json run_tiny(const Suite& suite, const fs::path& dir, int threads, std::optional<Shard> shard = {},
                     bool fresh = true) {
  SweepOptions o;
  o.threads = threads;
  o.shard = shard;
  o.journal_dir = (dir / "journal").string();
  o.fresh = fresh;
  return run_sweep(suite, o);
}

// One tiny sweep shared by the gate tests (they only read it).
const nlohmann::json& tiny_report() {
  static const nlohmann::json report = [] {
    const fs::path dir = fs::temp_directory_path() / ("bspbench_sweep_tiny_" + std::to_string(::getpid()));
    nlohmann::json r = run_tiny(tiny_suite(), dir, 2);
    fs::remove_all(dir);
    return r;
  }();
  return report;
}

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST(SweepSuites, EveryRegisteredHeuristicAndGeneratorIsSweptOnceEach) {
  for (const auto& suite : suites()) {
    SCOPED_TRACE(suite.name);
    const auto jobs = expand(suite);
    std::set<std::string> keys, scenes, heuristics_seen;
    for (const auto& j : jobs) {
      keys.insert(j.key);
      scenes.insert(j.scene);
      heuristics_seen.insert(j.heuristic);
    }
    EXPECT_EQ(keys.size(), jobs.size());
    EXPECT_EQ(scenes.size(), generators().size());
    EXPECT_EQ(heuristics_seen.size(), heuristics().size());
  }
}

TEST(SweepShards, PartitionTheSuiteDeterministically) {
  const auto jobs = expand(find_suite("quick"));
  std::multiset<std::string> seen;
  for (std::uint32_t i = 0; i < 3; ++i)
    for (const auto& j : shard_jobs(jobs, {i, 3})) seen.insert(j.key);
  EXPECT_EQ(seen.size(), jobs.size());
  EXPECT_EQ(std::set<std::string>(seen.begin(), seen.end()).size(), jobs.size());
  EXPECT_EQ(shard_jobs(jobs, parse_shard("1/3")).front().key, jobs[1].key);
  for (const char* bad : {"3/3", "1", "a/3", "1/0", "-1/3", "1/3x"}) EXPECT_THROW(parse_shard(bad), UsageError) << bad;
}

TEST(SweepJournal, TornLastLineIsDroppedAndTheNextAppendStartsAFreshLine) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "j.jsonl";
  std::ofstream(path) << R"({"key":"a","x":1})" << "\n" << R"({"key":"b","x":2})" << "\n" << R"({"key":"c","x)";
  {
    Journal j(path.string());
    ASSERT_EQ(j.records().size(), 2u);
    EXPECT_EQ(j.torn_lines(), 1u);
    j.append({{"key", "d"}});
  }
  const Journal again(path.string());
  ASSERT_EQ(again.records().size(), 3u);
  EXPECT_EQ(again.records()[2]["key"], "d");
  EXPECT_EQ(again.torn_lines(), 0u);
  fs::remove_all(dir);
}

TEST(SweepJournal, DamagedLineBeforeTheLastIsAnInputError) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "j.jsonl";
  std::ofstream(path) << R"({"key":"a"})" << "\n" << "garbage\n" << R"({"key":"b"})" << "\n";
  EXPECT_THROW(Journal(path.string()), InputError);
  fs::remove_all(dir);
}

TEST(SweepProgress, TerminalRewritesOneLineAndPlainOutputPrintsWholeLines) {
  std::ostringstream tty, plain;
  Progress on_tty(tty, true, 4, 4.0), on_log(plain, false, 4, 4.0);
  for (int i = 0; i < 4; ++i) {
    on_tty.job_done(1.0);
    on_log.job_done(1.0);  // well within kPlainInterval: no line yet
  }
  on_tty.finish();
  on_log.finish();
  const std::string t = tty.str(), p = plain.str();
  EXPECT_EQ(std::count(t.begin(), t.end(), '\r'), 5);
  EXPECT_NE(t.find("3/4 jobs"), std::string::npos);
  EXPECT_NE(t.find("left"), std::string::npos);
  EXPECT_EQ(p.find('\r'), std::string::npos);
  EXPECT_EQ(std::count(p.begin(), p.end(), '\n'), 1);
  EXPECT_NE(p.find("4/4 jobs"), std::string::npos);
}

TEST(SweepRunner, InterruptedSweepResumesWithoutRerunningFinishedJobs) {
  const fs::path dir = scratch_dir();
  const nlohmann::json complete = run_tiny(tiny_suite(), dir, 2);
  // Simulate kill -9 after five jobs, in the middle of writing the sixth.
  SweepOptions o;
  o.journal_dir = (dir / "journal").string();
  const fs::path journal = journal_path(tiny_suite(), o);
  const auto lines = lines_of(journal);
  ASSERT_EQ(lines.size(), complete["runs"].size());
  {
    std::ofstream out(journal, std::ios::trunc);
    for (int i = 0; i < 5; ++i) out << lines[i] << "\n";
    out << lines[5].substr(0, lines[5].size() / 2);
  }
  const nlohmann::json resumed = run_tiny(tiny_suite(), dir, 2, {}, false);
  EXPECT_EQ(deterministic_view(resumed), deterministic_view(complete));
  // The five journaled runs were taken as they were, timings included; the others ran again.
  std::set<std::string> kept;
  for (int i = 0; i < 5; ++i) kept.insert(nlohmann::json::parse(lines[i]).dump());
  std::size_t identical = 0;
  for (const auto& r : resumed["runs"]) identical += kept.count(r.dump());
  EXPECT_EQ(identical, 5u);
  EXPECT_EQ(lines_of(journal).size(), complete["runs"].size());
  fs::remove_all(dir);
}

TEST(SweepRunner, DeterministicFieldsDoNotDependOnTheThreadCount) {
  const fs::path dir = scratch_dir();
  const nlohmann::json one = run_tiny(tiny_suite(), dir / "1", 1);
  const nlohmann::json two = run_tiny(tiny_suite(), dir / "2", 2);
  EXPECT_EQ(one["summary"]["runs"], 16);
  EXPECT_TRUE(one["summary"]["complete"].get<bool>());
  EXPECT_EQ(deterministic_view(one), deterministic_view(two));
  EXPECT_NE(one["runs"][0]["timings"], nullptr);
  fs::remove_all(dir);
}

TEST(MergeReports, ShardsMergeToTheUnshardedReportAndBadSetsAreRejected) {
  const fs::path dir = scratch_dir();
  std::vector<NamedReport> shards;
  for (std::uint32_t i = 0; i < 3; ++i)
    shards.push_back({"shard" + std::to_string(i), run_tiny(tiny_suite(), dir, 2, Shard{i, 3})});
  EXPECT_EQ(deterministic_view(merge_reports(shards)), deterministic_view(tiny_report()));
  EXPECT_EQ(merge_reports(shards)["shards"].size(), 3u);

  auto duplicate = shards;
  duplicate[2] = duplicate[1];
  EXPECT_THROW(merge_reports(duplicate), InputError);
  auto missing = shards;
  missing.pop_back();
  EXPECT_THROW(merge_reports(missing), InputError);
  auto foreign = shards;
  foreign[1].report["suite"]["definition_hash"] = "0000000000000000";
  EXPECT_THROW(merge_reports(foreign), InputError);
  fs::remove_all(dir);
}

TEST(Aggregates, GrowthExponentOfAnExactPowerLawIsRecovered) {
  nlohmann::json runs = nlohmann::json::array();
  int key = 0;
  for (double n : {100.0, 1000.0, 10000.0})
    for (int seed = 1; seed <= 2; ++seed)
      runs.push_back({{"key", std::to_string(key++)},
                      {"id", {{"scene", "s"}, {"heuristic", "h"}, {"shape", "strict"}, {"scene_params", {{"n", n}}},
                              {"n", static_cast<std::uint64_t>(n)}, {"n_polygons", n}}},
                      {"metrics", {{"fragments", 3 * n * n}, {"nodes", 2 * n}}},
                      {"timings", {{"build_seconds", 1e-6 * n * std::sqrt(n)}}},
                      {"validation", nullptr}});
  const nlohmann::json agg = aggregate_runs(runs);
  ASSERT_EQ(agg.size(), 1u);
  EXPECT_NEAR(agg[0]["growth"]["fragments"]["exponent"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(agg[0]["growth"]["nodes"]["exponent"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(agg[0]["timing_growth"]["build_seconds"]["exponent"].get<double>(), 1.5, 1e-12);
  EXPECT_NEAR(agg[0]["growth"]["fragments"]["r2"].get<double>(), 1.0, 1e-12);
  ASSERT_EQ(agg[0]["by_n"].size(), 3u);
  EXPECT_EQ(agg[0]["by_n"][0]["metrics"]["fragments"]["mean"].get<double>(), 3e4);
}

class RegressGate : public ::testing::Test {
 protected:
  nlohmann::json baseline = tiny_report();
  nlohmann::json current = tiny_report();
  // A run whose build took long enough to be above the noise floor.
  static nlohmann::json& slow_run(nlohmann::json& report) {
    auto& run = report["runs"][3];
    run["timings"]["build_cpu_seconds"] = 0.5;
    return run;
  }
  bool fails() const { return compare_reports(baseline, current, {}).failed(); }
};

TEST_F(RegressGate, IdenticalReportPasses) {
  const RegressResult r = compare_reports(baseline, current, {});
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(r.runs_compared, 16u);
  EXPECT_GT(r.values_compared, 16u * 20);
}

TEST_F(RegressGate, OneChangedFragmentCountFails) {
  current["runs"][7]["metrics"]["fragments"] = current["runs"][7]["metrics"]["fragments"].get<std::uint64_t>() + 1;
  const RegressResult r = compare_reports(baseline, current, {});
  ASSERT_TRUE(r.failed());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_EQ(r.changes[0].field, "metrics.fragments");
}

TEST_F(RegressGate, FloatWithinTheRelativeToleranceMatchesAndBeyondItFails) {
  auto& e = current["runs"][0]["metrics"]["e_line"];
  const double v = e.get<double>();
  e = v * (1 + 0.5 * kFloatRelative);
  EXPECT_FALSE(fails());
  e = v * (1 + 4 * kFloatRelative);
  EXPECT_TRUE(fails());
}

TEST_F(RegressGate, TimingThreeTimesFasterOrSlowerFails) {
  slow_run(baseline);
  slow_run(current)["timings"]["build_cpu_seconds"] = 0.5 / 3;
  const RegressResult r = compare_reports(baseline, current, {});
  ASSERT_TRUE(r.failed());
  EXPECT_EQ(r.changes[0].what, "faster");
  EXPECT_EQ(r.changes[0].field, "timings.build_cpu_seconds");
  slow_run(current)["timings"]["build_cpu_seconds"] = 0.5 * 3;
  EXPECT_TRUE(fails());
  slow_run(current)["timings"]["build_cpu_seconds"] = 0.5 * 2.5;
  EXPECT_FALSE(fails());
  // Wall times are reported, not gated.
  slow_run(current)["timings"]["build_seconds"] = 100.0;
  EXPECT_FALSE(fails());
}

TEST_F(RegressGate, SlowerMachineWithSlowerCalibrationPasses) {
  slow_run(baseline);
  for (auto& run : current["runs"]) {
    for (auto& [k, v] : run["timings"].items()) v = v.get<double>() * 4;
    run["calibration_seconds"] = run["calibration_seconds"].get<double>() * 4;
  }
  slow_run(current)["timings"]["build_cpu_seconds"] = 0.5 * 4;
  EXPECT_FALSE(fails());
}

TEST_F(RegressGate, MissingRunAndViolationsFailButANewRunDoesNot) {
  current["runs"].erase(current["runs"].begin() + 2);
  EXPECT_TRUE(fails());
  current = tiny_report();
  current["runs"][1]["validation"]["violations"] = 1;
  baseline["runs"][1]["validation"]["violations"] = 1;
  EXPECT_TRUE(fails());
  current = tiny_report();
  baseline = tiny_report();
  baseline["runs"].erase(baseline["runs"].begin() + 2);
  EXPECT_FALSE(fails());
}

TEST(SweepReport, ReadingRejectsOtherSchemasVersionsAndDamagedRecords) {
  const fs::path dir = scratch_dir();
  const auto write_and_read = [&](const nlohmann::json& j) {
    std::ofstream(dir / "r.json") << j.dump();
    return read_report((dir / "r.json").string());
  };
  EXPECT_NO_THROW(write_and_read(tiny_report()));
  nlohmann::json other = tiny_report();
  other["version"] = kReportVersion + 1;
  EXPECT_THROW(write_and_read(other), InputError);
  other = tiny_report();
  other["schema"] = "something-else";
  EXPECT_THROW(write_and_read(other), InputError);
  other = tiny_report();
  other["runs"][0].erase("metrics");
  EXPECT_THROW(write_and_read(other), InputError);
  std::ofstream(dir / "r.json") << "{not json";
  EXPECT_THROW(read_report((dir / "r.json").string()), InputError);
  EXPECT_THROW(read_report((dir / "missing.json").string()), InputError);
  fs::remove_all(dir);
}
