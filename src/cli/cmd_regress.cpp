// bspbench regress: the regression gate between two reports (gate/regress.h says what is compared).
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/errors.h"
#include "gate/bench_gate.h"
#include "gate/regress.h"
#include "history/history.h"
#include "results/report.h"

namespace bsp::cli {

namespace {

// Whether the baseline is a Google Benchmark output (judged by gate/bench_gate.h) rather than a
// sweep report; anything unreadable goes to the report reader, whose error names the problem.
bool is_benchmark_file(const std::string& path) {
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  return !doc.is_discarded() && gate::is_benchmark_output(doc);
}

// The pooled last `k` entries of the current report's suite on its machine (history/history.h)
// before the current report: before its entry when it was appended already (neither it nor what
// came after judges it).
nlohmann::json history_baseline(const std::string& path, const nlohmann::json& current, std::size_t k) {
  const history::Database db = history::Database::open(path, false);
  const std::string suite = current["suite"]["name"].get<std::string>();
  const history::Machine machine = history::machine_of(current);
  const std::vector<history::Entry> entries = db.last(suite, machine.fingerprint, k, db.find(current));
  if (entries.empty())
    throw InputError(path + ": no earlier entry of suite " + suite + " on this machine (" + machine.cpu_model + ", " +
                     machine.fingerprint + ") to judge against");
  std::vector<nlohmann::json> reports;
  std::cout << "regress: against " << entries.size() << " entries of " << path << ":";
  for (const auto& e : entries) {
    std::cout << " " << e.id << " (" << e.revision << ")";
    reports.push_back(db.report(e.id));
  }
  std::cout << "\n";
  std::vector<const nlohmann::json*> pointers;
  for (const auto& r : reports) pointers.push_back(&r);
  return gate::pool_reports(pointers);
}

int run(Args& args) {
  const auto baseline = args.option("--baseline");
  const auto history_path = args.option("--history");
  const std::string current = args.required("--current");
  const auto last = args.integer("--last", 1, static_cast<long long>(history::kMaxLast));
  gate::RegressOptions options;
  options.time_tolerance = args.real("--time-tolerance").value_or(options.time_tolerance);
  options.alpha = args.real("--alpha").value_or(options.alpha);
  args.finish();
  if (baseline.has_value() == history_path.has_value()) throw UsageError("give either --baseline FILE or --history FILE.sqlite");
  if (last && !history_path) throw UsageError("--last goes with --history");
  if (history_path) {
    const nlohmann::json report = results::read_report(current);
    const std::size_t k = last ? static_cast<std::size_t>(*last) : history::kDefaultLast;
    const auto result = gate::compare_reports(history_baseline(*history_path, report, k), report, options);
    gate::print_regress(result, std::cout);
    return result.failed() ? 1 : 0;
  }
  const auto result =
      is_benchmark_file(*baseline)
          ? gate::compare_benchmarks(gate::read_benchmark_output(*baseline), gate::read_benchmark_output(current), options)
          : gate::compare_reports(results::read_report(*baseline), results::read_report(current), options);
  gate::print_regress(result, std::cout);
  return result.failed() ? 1 : 0;
}

}  // namespace

Command regress_command() {
  return {"regress", "(--baseline FILE | --history FILE.sqlite [--last K]) --current FILE [--time-tolerance X] [--alpha A]",
          "compare a report with a baseline; exit 1 on any changed result, violation or significant slowdown; "
          "given two Google Benchmark outputs of bspbench_bench_scaling, compare their ratios to the in-run references",
          run,
          {{"--baseline FILE", "the reference sweep report (results/baseline.json in CI) or benchmark output "
                               "(results/bench_scaling_ci.json)"},
           {"--history FILE.sqlite", "judge against the last K entries of the current report's suite on the same machine "
                                     "in this history database: results as the newest, timings pooled from all"},
           {"--last K", "with --history: how many entries (default 5)"},
           {"--current FILE", "the report or benchmark output to judge"},
           {"--time-tolerance X", "slowdown of a group's median build time that fails when significant, or of a "
                                  "benchmark's ratio to its reference (default 1.5)"},
           {"--alpha A", "significance level of the groups' Mann-Whitney U test (default 0.05)"}}};
}

}  // namespace bsp::cli
