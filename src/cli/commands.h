#pragma once
// The subcommands of the bspbench program. Each lives in its own cmd_*.cpp and is listed once in
// commands.cpp. run() returns the exit code; UsageError and InputError thrown from it become a
// one-line message and exit code 2 in main.cpp.
#include <string_view>
#include <vector>

#include "cli/args.h"

namespace bsp::cli {

struct Command {
  std::string_view name;
  std::string_view usage;    // the argument synopsis printed on a usage error
  std::string_view summary;  // one line for `bspbench --help`
  int (*run)(Args& args);
};

const std::vector<Command>& commands();

Command build_command();
Command compare_command();
Command heuristics_command();
Command scenes_command();
Command generate_command();
Command sweep_command();
Command merge_reports_command();
Command regress_command();
Command report_command();
Command order_command();
Command validate_command();

}  // namespace bsp::cli
