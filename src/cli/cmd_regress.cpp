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
  options.time_floor_seconds = args.real("--time-floor").value_or(options.time_floor_seconds);
  args.finish();
  const auto result =
      sweep::compare_reports(sweep::read_report(baseline), sweep::read_report(current), options);
  sweep::print_regress(result, std::cout);
  return result.failed() ? 1 : 0;
}

}  // namespace

Command regress_command() {
  return {"regress", "--baseline FILE --current FILE [--time-tolerance X] [--time-floor SECONDS]",
          "compare a report with a baseline; exit 1 on any changed result or timing past the tolerance", run};
}

}  // namespace bsp::cli
