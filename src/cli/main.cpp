// bspbench: the command-line front end. Exit codes: 0 success, 1 a check failed (validation
// violations, a regression), 2 bad arguments or bad input.
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "common/errors.h"

namespace {

void print_help() {
  std::cout << "usage: bspbench COMMAND [options]\n\ncommands:\n";
  for (const auto& c : bsp::cli::commands()) std::cout << "  " << c.name << "\t" << c.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    print_help();
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& command : bsp::cli::commands()) {
    if (command.name != name) continue;
    bsp::cli::Args args(std::vector<std::string>(argv + 2, argv + argc));
    try {
      return command.run(args);
    } catch (const bsp::UsageError& e) {
      std::cerr << "bspbench " << name << ": " << e.what() << "\nusage: bspbench " << name << " " << command.usage
                << "\n";
      return 2;
    } catch (const bsp::InputError& e) {
      std::cerr << "bspbench " << name << ": " << e.what() << "\n";
      return 2;
    }
  }
  std::cerr << "bspbench: unknown command '" << name << "'; run bspbench --help\n";
  return 2;
}
