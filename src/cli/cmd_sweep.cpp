// bspbench sweep: run a suite (or one shard of it) and write the report.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "sweep/report.h"
#include "sweep/runner.h"

namespace bsp::cli {

namespace {

// Failed jobs and violations are results: they are in the report (and fail the regression gate),
// so the sweep names them on stderr and still exits 0 once the report is written.
void summarize(const nlohmann::json& report, const std::string& out) {
  const auto& s = report["summary"];
  std::cout << "sweep: wrote " << out << ": " << s["runs"] << " runs, " << s["failures"] << " failed jobs, "
            << s["invariant_violations"] << " invariant and " << s["validation_violations"]
            << " validation violations\n";
  for (const auto& f : report["failures"])
    std::cerr << "sweep: job " << f["id"]["command"].get<std::string>() << " failed: " << f["error"].get<std::string>()
              << "\n";
  for (const auto& r : report["runs"]) {
    const bool broken = r["invariants"]["violations"] != 0 ||
                        (r["validation"].is_object() && r["validation"]["violations"] != 0);
    if (broken) std::cerr << "sweep: violations in " << r["id"]["command"].get<std::string>() << "\n";
  }
}

int run(Args& args) {
  const std::string suite_name = args.required("--suite");
  sweep::SweepOptions options;
  options.threads = static_cast<int>(args.integer("--threads", 1, 1024).value_or(0));
  if (const auto shard = args.option("--shard")) options.shard = sweep::parse_shard(*shard);
  const std::string out = args.option("--out").value_or("results/report.json");
  const auto journal_dir = args.option("--journal-dir");
  options.fresh = args.flag("--fresh");
  args.finish();
  const sweep::Suite& suite = sweep::find_suite(suite_name);
  options.journal_dir = journal_dir.value_or((std::filesystem::path(out).parent_path() / "journal").string());
  options.log = &std::cerr;
  options.log_is_terminal = ::isatty(STDERR_FILENO) != 0;
  const nlohmann::json report = sweep::run_sweep(suite, options);
  sweep::write_report(out, report);
  summarize(report, out);
  return 0;
}

}  // namespace

Command sweep_command() {
  return {"sweep",
          "--suite smoke|quick|default|full [--threads N] [--shard i/N] [--out FILE] [--journal-dir DIR] [--fresh]",
          "run a suite of builds (scenes x heuristics x seeds x sizes), resumable, and write its report", run};
}

}  // namespace bsp::cli
