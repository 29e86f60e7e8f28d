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

#include <nlohmann/json_fwd.hpp>

namespace bsp::cli {

// Writes `data` as DIR/NAME (DIR created when missing; a temporary file renamed into place), for a
// script to draw and beside the page it explains; returns the path. Throws InputError naming what
// cannot be made or written.
std::string write_page_data(const std::string& dir, const std::string& name, const nlohmann::json& data);

// Runs `python SCRIPT ARGS...` and returns its exit status (128 + signal when killed). Throws
// InputError when the script cannot be found or the interpreter not started.
int run_analysis_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace bsp::cli
