#pragma once
// Running the real bspbench binary (BSPBENCH_EXE) from tests, with its exit code and output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace bsp::testing {

struct CliResult {
  int code = -1;  // exit code; -1 when the process did not exit normally
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// An empty scratch directory for the running test: PREFIX_<test name>_<pid> in the temp folder, so
// parallel ctest runs never share one. The caller removes it.
inline std::filesystem::path fresh_test_dir(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::temp_directory_path() /
                   (prefix + "_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `bspbench ARGS` (ARGS is shell text), capturing stdout and stderr in files under `dir`.
inline CliResult run_bspbench(const std::string& args, const std::filesystem::path& dir) {
  const std::string cmd = std::string(BSPBENCH_EXE) + " " + args + " > " + (dir / "stdout").string() + " 2> " +
                          (dir / "stderr").string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"), slurp(dir / "stderr")};
}

}  // namespace bsp::testing
