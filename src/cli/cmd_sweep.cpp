// bspbench sweep: run a suite (or one shard of it) and write the report. The environment variable
// BSPBENCH_PLANT_SLOWDOWN=heuristic:factor is for tests only (experiments/timing.h): it slows one
// heuristic's timed builds down, so the regression gate can be shown to catch it.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/errors.h"
#include "history/history.h"
#include "results/record.h"
#include "results/report.h"
#include "sweep/runner.h"
#include "suite/catalog.h"

namespace bsp::cli {

namespace {

// Failed jobs and violations are results: they are in the report (and fail the regression gate),
// so the sweep names them on stderr and still exits 0 once the report is written.
void summarize(const nlohmann::json& report, const std::string& out) {
  const auto& s = report["summary"];
  std::cout << "sweep: wrote " << out << ": " << s["runs"] << " runs, " << s["failures"] << " failed jobs, "
            << s["invariant_violations"] << " invariant and " << s["validation_violations"]
            << " validation violations, " << s["ray_shoot_mismatches"] << " ray-shooting mismatches";
  if (s.contains("others_violations") && s["others_violations"] != 0)
    std::cout << " (and " << s["others_violations"] << " in nodes made by external builders or shipped with a WAD)";
  std::cout << "\n";
  for (const auto& f : report["failures"])
    std::cerr << "sweep: job " << f["id"]["command"].get<std::string>() << " failed: " << f["error"].get<std::string>()
              << "\n";
  for (const auto& r : report["runs"]) {
    if (!results::judged_for_violations(r["id"])) continue;  // facts about another builder's nodes
    const bool broken = r["invariants"]["violations"] != 0 ||
                        (r["validation"].is_object() && r["validation"]["violations"] != 0) ||
                        (r.contains("ray_shooting") && r["ray_shooting"].is_object() &&
                         r["ray_shooting"]["mismatches"] != 0);
    if (broken) std::cerr << "sweep: violations in " << r["id"]["command"].get<std::string>() << "\n";
  }
}

void append_to_history(history::Database& db, const nlohmann::json& report) {
  const history::Entry e = db.append(std::span(&report, 1)).front();
  std::cout << "sweep: appended to " << db.path() << " as entry " << e.id << " (revision " << e.revision << ", machine "
            << e.machine.fingerprint << ")\n";
}

int run(Args& args) {
  const std::string suite_name = args.required("--suite");
  sweep::SweepOptions options;
  options.threads = static_cast<int>(args.integer("--threads", 1, 1024).value_or(0));
  if (const auto shard = args.option("--shard")) options.shard = suite::parse_shard(*shard);
  const std::string out = args.option("--out").value_or("results/report.json");
  const auto journal_dir = args.option("--journal-dir");
  options.fresh = args.flag("--fresh");
  const auto history_path = args.option("--history");
  args.finish();
  if (history_path && options.shard)
    throw UsageError("a shard's report is one part of a sweep: append the merged one (merge-reports --history)");
  // Opened first: a database that is not one stops the sweep before it runs.
  std::optional<history::Database> history;
  if (history_path) history = history::Database::open(*history_path, true);
  if (const char* plant = std::getenv("BSPBENCH_PLANT_SLOWDOWN")) options.plant = experiments::parse_planted_slowdown(plant);
  const suite::Suite suite = suite::find_suite(suite_name);
  options.journal_dir = journal_dir.value_or((std::filesystem::path(out).parent_path() / "journal").string());
  // std::clog, not std::cerr: the same stderr, but a stream whose buffer no mesh reader swaps out
  // while a job reads a file (io/mesh_reader_cgal.cpp quiets CGAL through std::cerr).
  options.log = &std::clog;
  options.log_is_terminal = ::isatty(STDERR_FILENO) != 0;
  const nlohmann::json report = sweep::run_sweep(suite, options);
  results::write_report(out, report);
  summarize(report, out);
  if (history) append_to_history(*history, report);
  return 0;
}

}  // namespace

Command sweep_command() {
  return {"sweep",
          "--suite NAME|FILE.json [--threads N] [--shard i/N] [--out FILE] [--journal-dir DIR] [--fresh] [--history FILE.sqlite]",
          "run a suite of builds (scenes x heuristics x seeds x sizes), resumable, and write its report", run,
          {{"--suite NAME|FILE.json",
            "a built-in suite: smoke, quick, default, merge, dynamic, occlusion, segments, doom or full "
            "(analysis/suites/NAME.json; docs/results/suites.md gives their run times); or your own suite file, taken as a file when it "
            "ends in .json or holds a '/' (analysis/SUITE_SCHEMA.md)"},
           {"--threads N", "jobs run at once (default: OMP_NUM_THREADS or the core count)"},
           {"--shard i/N", "run only share i of N (0-based) of the suite's jobs; merge with merge-reports"},
           {"--out FILE", "the report (default results/report.json)"},
           {"--journal-dir DIR", "where finished jobs are journaled for resuming (default: journal/ beside --out)"},
           {"--fresh", "discard the journal and run every job again"},
           {"--history FILE.sqlite", "append the report to this history database (created if missing; bspbench history "
                                     "draws it); a sharded sweep appends with merge-reports instead"}}};
}

}  // namespace bsp::cli
