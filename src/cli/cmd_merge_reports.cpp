// bspbench merge-reports: combine the reports of a sharded sweep into one.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/errors.h"
#include "results/shards.h"
#include "results/report.h"

namespace bsp::cli {

namespace {

int run(Args& args) {
  const std::string out = args.required("--out");
  const std::vector<std::string> files = args.positional();
  args.finish();
  if (files.empty()) throw UsageError("give the shards' report files");
  std::vector<results::NamedReport> inputs;
  for (const auto& f : files) inputs.push_back({f, results::read_report(f)});
  const nlohmann::json merged = results::combine_shards(inputs);
  results::write_report(out, merged);
  std::cout << "merge-reports: wrote " << out << ": " << merged["shards"].size() << " shards, "
            << merged["summary"]["runs"] << " runs\n";
  return 0;
}

}  // namespace

Command merge_reports_command() {
  return {"merge-reports", "--out FILE REPORT...",
          "combine the reports of --shard i/N sweeps (all N shards of one suite) into one report", run,
          {{"--out FILE", "the merged report"}, {"REPORT...", "the N shard reports, in any order"}}};
}

}  // namespace bsp::cli
