// bspbench regress: the regression gate between two reports (gate/regress.h says what is compared).
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "gate/bench_gate.h"
#include "gate/regress.h"
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

int run(Args& args) {
  const std::string baseline = args.required("--baseline");
  const std::string current = args.required("--current");
  gate::RegressOptions options;
  options.time_tolerance = args.real("--time-tolerance").value_or(options.time_tolerance);
  options.alpha = args.real("--alpha").value_or(options.alpha);
  args.finish();
  const auto result =
      is_benchmark_file(baseline)
          ? gate::compare_benchmarks(gate::read_benchmark_output(baseline), gate::read_benchmark_output(current), options)
          : gate::compare_reports(results::read_report(baseline), results::read_report(current), options);
  gate::print_regress(result, std::cout);
  return result.failed() ? 1 : 0;
}

}  // namespace

Command regress_command() {
  return {"regress", "--baseline FILE --current FILE [--time-tolerance X] [--alpha A]",
          "compare a report with a baseline; exit 1 on any changed result, violation or significant slowdown; "
          "given two Google Benchmark outputs of bspbench_bench_scaling, compare their ratios to the in-run references",
          run,
          {{"--baseline FILE", "the reference sweep report (results/baseline.json in CI) or benchmark output "
                               "(results/bench_scaling_ci.json)"},
           {"--current FILE", "the report or benchmark output to judge"},
           {"--time-tolerance X", "slowdown of a group's median build time that fails when significant, or of a "
                                  "benchmark's ratio to its reference (default 1.5)"},
           {"--alpha A", "significance level of the groups' Mann-Whitney U test (default 0.05)"}}};
}

}  // namespace bsp::cli
