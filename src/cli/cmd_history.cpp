// bspbench history: results over time (history/history.h). Appends reports to a history database
// and draws its page: every gated timing group and metric over the database's entries, the gate's
// decision on each entry marked, a change of machine shown as a break (analysis/history.py).
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/analysis_script.h"
#include "cli/commands.h"
#include "cli/guard.h"
#include "common/errors.h"
#include "common/progress.h"
#include "history/history.h"
#include "history/page_data.h"
#include "results/report.h"

namespace bsp::cli {

namespace {

namespace fs = std::filesystem;

int run(Args& args) {
  const std::string db_path = args.required("--db");
  const std::vector<std::string> appends = args.options("--append");
  const auto out = args.option("--out");
  history::PageSettings settings;
  settings.suite = args.option("--suite");
  settings.last = static_cast<std::size_t>(
      args.integer("--last", 1, static_cast<long long>(history::kMaxLast)).value_or(static_cast<long long>(settings.last)));
  args.finish();
  if (appends.empty() && !out) throw UsageError("give --append REPORT.json, --out DIR, or both");
  // Every report is read, and all appended in one transaction: a bad one appends none.
  std::vector<nlohmann::json> reports;
  for (const auto& a : appends) reports.push_back(results::read_report(a));
  history::Database db = history::Database::open(db_path, !appends.empty());
  const std::vector<history::Entry> entries = db.append(reports);  // none: nothing written
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const history::Entry& e = entries[i];
    std::cout << "history: appended " << appends[i] << " to " << db_path << " as entry " << e.id << " (" << e.suite << ", "
              << e.revision << ", machine " << e.machine.fingerprint << ")\n";
  }
  if (!out) return 0;
  // Progress on stderr: reading and judging the entries, each weighing as its runs; the drawing
  // (analysis/history.py) shows its own.
  std::uint64_t runs = 0, count = 0;
  for (const history::Entry& e : db.entries(settings.suite)) runs += e.runs, ++count;
  Progress progress(std::clog, ::isatty(STDERR_FILENO) != 0, "history", "entries", count, static_cast<double>(runs));
  settings.on_entry = [&](std::uint64_t entry_runs) { progress.job_done(static_cast<double>(entry_runs)); };
  const nlohmann::json data_json = history::page_data(db, settings);
  progress.finish();
  // history.json beside the page: for the script, and for readers who want the numbers.
  const std::string data = write_page_data(*out, "history.json", data_json);
  const int status = run_analysis_script("history.py", {"--data", data, "--out", *out});
  if (status == 0) std::cout << "history: wrote " << (fs::path(*out) / "index.html").string() << "\n";
  // history.py exits 2 on bad data; anything else (no matplotlib, a crash) is not the user's.
  return status == 0 ? 0 : status == 2 ? 2 : kExitInternal;
}

}  // namespace

Command history_command() {
  return {"history", "--db FILE.sqlite [--append REPORT.json]... [--out DIR] [--suite NAME] [--last K]",
          "keep reports in a history database and draw every gated metric and timing over revisions as DIR/index.html",
          run,
          {{"--db FILE.sqlite", "the history database (created by the first --append; sweep --history appends too)"},
           {"--append REPORT.json", "append a report of sweep or merge-reports (repeatable; all are read before any is appended)"},
           {"--out DIR", "draw the page: index.html, its plots and history.json (the numbers drawn)"},
           {"--suite NAME", "only this suite's entries (default: every suite, a section each)"},
           {"--last K", "the gate judges each entry against the last K entries of its suite and machine before it, "
                        "as regress --history does (default 5)"}}};
}

}  // namespace bsp::cli
