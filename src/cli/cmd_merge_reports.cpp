// bspbench merge-reports: combine the reports of a sharded sweep into one.
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/errors.h"
#include "history/history.h"
#include "results/shards.h"
#include "results/report.h"

namespace bsp::cli {

namespace {

int run(Args& args) {
  const std::string out = args.required("--out");
  const auto history_path = args.option("--history");
  const std::vector<std::string> files = args.positional();
  args.finish();
  if (files.empty()) throw UsageError("give the shards' report files");
  std::optional<history::Database> history;
  if (history_path) history = history::Database::open(*history_path, true);
  std::vector<results::NamedReport> inputs;
  for (const auto& f : files) inputs.push_back({f, results::read_report(f)});
  const nlohmann::json merged = results::combine_shards(inputs);
  results::write_report(out, merged);
  std::cout << "merge-reports: wrote " << out << ": " << merged["shards"].size() << " shards, "
            << merged["summary"]["runs"] << " runs\n";
  if (history) {
    const history::Entry e = history->append(std::span(&merged, 1)).front();
    std::cout << "merge-reports: appended to " << history->path() << " as entry " << e.id << "\n";
  }
  return 0;
}

}  // namespace

Command merge_reports_command() {
  return {"merge-reports", "--out FILE [--history FILE.sqlite] REPORT...",
          "combine the reports of --shard i/N sweeps (all N shards of one suite) into one report", run,
          {{"--out FILE", "the merged report"},
           {"--history FILE.sqlite", "append the merged report to this history database (created if missing)"},
           {"REPORT...", "the N shard reports, in any order"}}};
}

}  // namespace bsp::cli
