#include "cli/commands.h"

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
      report_command(),
      order_command(),
      validate_command(),
  };
  return all;
}

}  // namespace bsp::cli
