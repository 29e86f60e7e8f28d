#pragma once
// Where `bspbench sweep --suite ARG` finds its suite. The built-in suites are data: the JSON files
// of analysis/suites/ (one per suite, named by its file), compiled into the binary and read by the
// same parser as a user's suite file (suite_file.h). A user's file may not take a built-in's name,
// unless it is that built-in's own file, so a report's suite name always says which suite ran.
#include <string>
#include <string_view>
#include <vector>

#include "sweep/suite.h"

namespace bsp::sweep {

// The built-in suites' names, sorted.
std::vector<std::string> builtin_suite_names();

// A suite file when ARG names one (names_suite_file), else the built-in suite of that name.
// Throws UsageError naming the built-in suites for an unknown name, InputError for a bad file.
Suite find_suite(std::string_view arg);

}  // namespace bsp::sweep
