// bspbench regress: the regression gate between two reports (sweep/regress.h says what is compared).
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "sweep/regress.h"
#include "sweep/report.h"

namespace bsp::cli {

namespace {

int run(Args& args) {
  const std::string baseline = args.required("--baseline");
  const std::string current = args.required("--current");
  sweep::RegressOptions options;
  options.time_tolerance = args.real("--time-tolerance").value_or(options.time_tolerance);
  options.alpha = args.real("--alpha").value_or(options.alpha);
  args.finish();
  const auto result =
      sweep::compare_reports(sweep::read_report(baseline), sweep::read_report(current), options);
  sweep::print_regress(result, std::cout);
  return result.failed() ? 1 : 0;
}

}  // namespace

Command regress_command() {
  return {"regress", "--baseline FILE --current FILE [--time-tolerance X] [--alpha A]",
          "compare a report with a baseline; exit 1 on any changed result, violation or significant slowdown", run,
          {{"--baseline FILE", "the reference report (results/baseline.json in CI)"},
           {"--current FILE", "the report to judge"},
           {"--time-tolerance X", "slowdown of a group's median build time that fails when significant (default 1.5)"},
           {"--alpha A", "significance level of the groups' Mann-Whitney U test (default 0.05)"}}};
}

}  // namespace bsp::cli
