#include "cli/commands.h"

#include <algorithm>
#include <ostream>
#include <string>

namespace bsp::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      build_command(),
      compare_command(),
      heuristics_command(),
      scenes_command(),
      generate_command(),
      sweep_command(),
      merge_reports_command(),
      regress_command(),
      history_command(),
      report_command(),
      order_command(),
      validate_command(),
      merge_command(),
      csg_command(),
      classify_command(),
      animate_command(),
      occlude_command(),
      doom_command(),
      kernel_command(),
      optimal_command(),
  };
  return all;
}

void print_command_help(const Command& command, std::ostream& out) {
  out << "usage: bspbench " << command.name << " " << command.usage << "\n" << command.summary << "\n";
  if (command.options.empty()) return;
  std::size_t width = 0;
  for (const auto& o : command.options) width = std::max(width, o.option.size());
  out << "\noptions:\n";
  for (const auto& o : command.options)
    out << "  " << o.option << std::string(width - o.option.size(), ' ') << "  " << o.meaning << "\n";
}

OptionHelps concat(std::initializer_list<OptionHelps> lists) {
  OptionHelps out;
  for (const auto& l : lists) out.insert(out.end(), l.begin(), l.end());
  return out;
}

}  // namespace bsp::cli
