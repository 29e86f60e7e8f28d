// bspbench: the command-line front end. Exit codes:
//   0  success (and `--help`, `COMMAND --help`, `--version`)
//   1  a check failed (validation violations, a regression)
//   2  bad arguments or bad input: one line naming the problem (and the usage line for arguments)
//   3  an exception thrown by a plugin's code, reported as one line naming the plugin; or an
//      internal error: any other exception (out of memory, an Embree error, a bug), reported as one
//      line "bspbench COMMAND: internal error: ..." instead of std::terminate (cli/guard.h)
// Every command takes --plugin PATH.so, repeatable: the plugin's heuristics are registered before
// the command runs (experiments/plugin_loader.h).
#include <algorithm>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.h"
#include "cli/guard.h"
#include "common/errors.h"
#include "common/revision.h"
#include "experiments/plugin_loader.h"

namespace {

void print_help() {
  std::cout << "usage: bspbench COMMAND [options] [--plugin PATH.so ...]   (bspbench COMMAND --help for its options)\n"
               "       bspbench --version\n\n"
               "--plugin PATH.so (any command, repeatable) registers a plugin's heuristics (examples/my_heuristic)\n\n"
               "commands:\n";
  for (const auto& c : bsp::cli::commands()) std::cout << "  " << c.name << "\t" << c.summary << "\n";
}

bool asks_for_help(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; });
}

// Takes every "--plugin PATH" and "--plugin=PATH" out of `args` and loads the plugins. Throws
// UsageError for a --plugin without a path, InputError or PluginError for a bad plugin.
void load_plugins(std::vector<std::string>& args) {
  constexpr std::string_view kJoined = "--plugin=";
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i].starts_with(kJoined)) {
      bsp::experiments::load_plugin(args[i].substr(kJoined.size()));
    } else if (args[i] == "--plugin") {
      if (i + 1 == args.size() || args[i + 1].empty()) throw bsp::UsageError("--plugin needs the path of a plugin (a .so)");
      bsp::experiments::load_plugin(args[++i]);
    } else {
      rest.push_back(std::move(args[i]));
    }
  }
  args = std::move(rest);
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
    return bsp::cli::run_guarded(command.name, command.usage, [&] {
      load_plugins(rest);
      bsp::cli::Args args(std::move(rest));
      return command.run(args);
    }, std::cerr);
  }
  std::cerr << "bspbench: unknown command '" << first << "'; run bspbench --help\n";
  return 2;
}
