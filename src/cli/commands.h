#pragma once
// The subcommands of the bspbench program. Each lives in its own cmd_*.cpp and is listed once in
// commands.cpp. run() returns the exit code; what it throws becomes a one-line message and an exit
// code in main.cpp (cli/guard.h).
#include <initializer_list>
#include <iosfwd>
#include <string_view>
#include <vector>

#include "cli/args.h"

namespace bsp::cli {

struct Command {
  std::string_view name;
  std::string_view usage;    // the argument synopsis printed on a usage error and by --help
  std::string_view summary;  // one line for `bspbench --help`
  int (*run)(Args& args);
  OptionHelps options;       // every option of the usage line with its meaning, for `bspbench NAME --help`
};

const std::vector<Command>& commands();

// `bspbench NAME --help`: the usage line, the summary and one line per option.
void print_command_help(const Command& command, std::ostream& out);

// The options several commands share.
OptionHelps concat(std::initializer_list<OptionHelps> lists);
inline const OptionHelps kJsonOption = {{"--json", "print one JSON object instead of text"}};

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
Command merge_command();
Command csg_command();
Command classify_command();
Command animate_command();
Command occlude_command();
Command doom_command();
Command kernel_command();
Command optimal_command();
Command history_command();

}  // namespace bsp::cli
