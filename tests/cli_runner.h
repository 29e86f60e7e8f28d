#pragma once
// Running the real bspbench binary (BSPBENCH_EXE) from tests, with its exit code and output.
#include <gtest/gtest.h>
#include <sys/resource.h>
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

struct LimitedResult {
  CliResult result;
  long max_rss_kb = -1;       // the child's peak resident set
  double cpu_seconds = -1.0;  // user + system time of the child
};

// run_bspbench in a child whose address space and CPU time are capped (RLIMIT_AS, RLIMIT_CPU), so a
// run that tries to allocate what it should not fails fast instead of exhausting the machine, and
// with the child's peak memory and CPU time from wait4. Under AddressSanitizer, which reserves
// terabytes of shadow address space, only the CPU limit applies; the peak memory is still measured.
inline LimitedResult run_bspbench_limited(const std::string& args, const std::filesystem::path& dir,
                                          rlim_t address_space_bytes, rlim_t cpu_seconds) {
  const std::string cmd = std::string(BSPBENCH_EXE) + " " + args + " > " + (dir / "stdout").string() + " 2> " +
                          (dir / "stderr").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const rlimit cpu{cpu_seconds, cpu_seconds};
    ::setrlimit(RLIMIT_CPU, &cpu);
#if !defined(__SANITIZE_ADDRESS__)
    const rlimit as{address_space_bytes, address_space_bytes};
    ::setrlimit(RLIMIT_AS, &as);
#else
    (void)address_space_bytes;
#endif
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  LimitedResult r;
  r.result = {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"), slurp(dir / "stderr")};
  r.max_rss_kb = usage.ru_maxrss;
  r.cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return r;
}

}  // namespace bsp::testing
