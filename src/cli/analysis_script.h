#pragma once
// Running a script of analysis/ (report.py, history.py) with Debian's Python, which has matplotlib
// (a pyenv python3 on PATH may not): the commands that draw pages.
//
// A script is looked up in BSPBENCH_SOURCE_DIR/analysis (the source tree this binary was built
// from, a compile definition), then in analysis/ next to the executable (for a copied or installed
// binary). The interpreter is /usr/bin/python3 unless the BSPBENCH_PYTHON environment variable
// names another one.
#include <string>
#include <vector>

namespace bsp::cli {

// Runs `python SCRIPT ARGS...` and returns its exit status (128 + signal when killed). Throws
// InputError when the script cannot be found or the interpreter not started.
int run_analysis_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace bsp::cli
