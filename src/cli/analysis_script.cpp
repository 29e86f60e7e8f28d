#include "cli/analysis_script.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "io/atomic_file.h"

namespace bsp::cli {

namespace {

namespace fs = std::filesystem;

constexpr const char* kDefaultPython = "/usr/bin/python3";

fs::path find_script(const std::string& name) {
  const fs::path in_source = fs::path(BSPBENCH_SOURCE_DIR) / "analysis" / name;
  if (fs::exists(in_source)) return in_source;
  std::error_code ec;
  const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / "analysis" / name;
  if (!ec && fs::exists(beside)) return beside;
  throw InputError("cannot find analysis/" + name + " (looked in " + in_source.string() + " and " + beside.string() + ")");
}

// Runs argv; returns its exit status (128 + signal when killed).
int spawn(const std::vector<std::string>& argv) {
  std::vector<char*> c_argv;
  for (const auto& a : argv) c_argv.push_back(const_cast<char*>(a.c_str()));
  c_argv.push_back(nullptr);
  std::cout.flush();
  const pid_t pid = ::fork();
  if (pid < 0) throw InputError(std::string("cannot start ") + argv[0] + ": " + std::strerror(errno));
  if (pid == 0) {
    ::execv(c_argv[0], c_argv.data());
    std::cerr << "bspbench: cannot run " << argv[0] << ": " << std::strerror(errno) << "\n";
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw InputError(std::string("lost ") + argv[0] + ": " + std::strerror(errno));
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::string write_page_data(const std::string& dir, const std::string& name, const nlohmann::json& data) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create the output directory (" + ec.message() + ")");
  const std::string path = (fs::path(dir) / name).string();
  write_file_atomically(path, data.dump(1) + "\n");
  return path;
}

int run_analysis_script(const std::string& script, const std::vector<std::string>& args) {
  const char* python = std::getenv("BSPBENCH_PYTHON");
  std::vector<std::string> argv = {python ? python : kDefaultPython, find_script(script).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return spawn(argv);
}

}  // namespace bsp::cli
