#pragma once
// Where `bspbench sweep --suite ARG` finds its suite. The built-in suites are data: the JSON files
// of analysis/suites/ (one per suite, named by its file), compiled into the binary
// (cmake/embed_suites.cmake) and read by the same parser as a user's suite file. A user's file may
// not take a built-in's name, unless it is that built-in's own file, so a report's suite name
// always says which suite ran.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "suite/suite.h"

namespace bsp::suite {

// The built-in suites' names, sorted.
std::vector<std::string> builtin_suite_names();

// A suite file when ARG names one (names_suite_file), else the built-in suite of that name.
// Throws UsageError naming the built-in suites for an unknown name, InputError for a bad file.
Suite find_suite(std::string_view arg);

// The compiled-in files (the definition is generated).
struct EmbeddedSuite {
  std::string_view name;  // the file's stem, which is the suite's name
  std::string_view path;  // relative to the repository, e.g. analysis/suites/quick.json
  std::string_view text;
};
// Sorted by path.
std::span<const EmbeddedSuite> embedded_suites();

}  // namespace bsp::suite
