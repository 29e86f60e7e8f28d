// bspbench: the command-line front end. Exit codes:
//   0  success (and `--help`, `COMMAND --help`, `--version`)
//   1  a check failed (validation violations, a regression)
//   2  bad arguments or bad input: one line naming the problem (and the usage line for arguments)
//   3  an internal error: any other exception (out of memory, an Embree error, a bug), reported as
//      one line "bspbench COMMAND: internal error: ..." instead of std::terminate (cli/guard.h)
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/guard.h"
#include "common/revision.h"

namespace {

void print_help() {
  std::cout << "usage: bspbench COMMAND [options]   (bspbench COMMAND --help for its options)\n"
               "       bspbench --version\n\ncommands:\n";
  for (const auto& c : bsp::cli::commands()) std::cout << "  " << c.name << "\t" << c.summary << "\n";
}

bool asks_for_help(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; });
}

}  // namespace

int main(int argc, char** argv) {
  const std::string first = argc < 2 ? "" : argv[1];
  if (argc < 2 || first == "--help" || first == "-h") {
    print_help();
    return argc < 2 ? 2 : 0;
  }
  if (first == "--version") {
    std::cout << "bspbench " << bsp::project_version() << " (revision " << bsp::git_revision() << ")\n";
    return 0;
  }
  for (const auto& command : bsp::cli::commands()) {
    if (command.name != first) continue;
    std::vector<std::string> rest(argv + 2, argv + argc);
    if (asks_for_help(rest)) {
      bsp::cli::print_command_help(command, std::cout);
      return 0;
    }
    bsp::cli::Args args(std::move(rest));
    return bsp::cli::run_guarded(command.name, command.usage, [&] { return command.run(args); }, std::cerr);
  }
  std::cerr << "bspbench: unknown command '" << first << "'; run bspbench --help\n";
  return 2;
}
