#include "experiments/doom/node_builders.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>

#include "common/errors.h"

extern char** environ;

namespace bsp::experiments {

namespace {

struct BuilderSpec {
  std::string name;
  std::vector<std::string> (*arguments)(const std::string& in, const std::string& out);
  std::vector<std::string> version_arguments;  // a command that prints the banner and exits
};

const std::vector<BuilderSpec>& specs() {
  static const std::vector<BuilderSpec> all = {
      {"zdbsp", [](const std::string& in, const std::string& out) { return std::vector<std::string>{"-o", out, in}; },
       {"-V"}},
      // glBSP prints its banner before anything else, usage included.
      {"glbsp", [](const std::string& in, const std::string& out) { return std::vector<std::string>{"-n", in, "-o", out}; },
       {"-help"}},
  };
  return all;
}

const BuilderSpec& spec_of(const std::string& builder) {
  for (const BuilderSpec& s : specs())
    if (s.name == builder) return s;
  std::string names;
  for (const BuilderSpec& s : specs()) names += (names.empty() ? "" : ", ") + s.name;
  throw UsageError("unknown node builder '" + builder + "' (known: " + names + ")");
}

std::string on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    struct stat st{};
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return "";
}

double seconds_of(const timeval& tv) { return static_cast<double>(tv.tv_sec) + 1e-6 * static_cast<double>(tv.tv_usec); }

struct Child {
  pid_t pid = -1;
  int output = -1;  // read end of the pipe the child writes stdout and stderr to
};

// posix_spawn rather than fork: no copy of a large parent's page tables, and no shell.
Child spawn(const std::string& program, const std::vector<std::string>& arguments, std::string& error) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    error = "cannot create a pipe";
    return {};
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Child child;
  const int rc = posix_spawnp(&child.pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (rc != 0) {
    close(fds[0]);
    error = program + ": cannot start: " + std::strerror(rc);
    return {};
  }
  child.output = fds[0];
  return child;
}

// Reads the child's output until it closes it or the deadline passes; false on the deadline.
bool collect_output(int fd, std::chrono::steady_clock::time_point deadline, std::string& log) {
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000))) < 0 && errno != EINTR) return true;
    if (p.revents == 0) continue;
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    log.append(buffer, static_cast<size_t>(n));
  }
}

// Runs `program` to its end or the timeout; the builder's own failures are recorded, never thrown.
void run_child(const std::string& program, const std::vector<std::string>& arguments, double timeout_s,
               BuilderRun& run) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  const Child child = spawn(program, arguments, error);
  if (child.pid < 0) {
    run.log = error;
    return;
  }
  const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(timeout_s));
  run.timed_out = !collect_output(child.output, deadline, run.log);
  if (run.timed_out) kill(child.pid, SIGKILL);
  close(child.output);
  int status = 0;
  rusage usage{};
  while (wait4(child.pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_seconds = seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
  if (WIFEXITED(status) && !run.timed_out) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status) && !run.timed_out) run.log += "\nkilled by signal " + std::to_string(WTERMSIG(status));
}

std::string last_line(std::string_view log) {
  while (!log.empty() && (log.back() == '\n' || log.back() == '\r' || log.back() == ' ')) log.remove_suffix(1);
  const size_t from = log.find_last_of("\r\n");
  return std::string(from == std::string_view::npos ? log : log.substr(from + 1));
}

}  // namespace

std::string BuilderRun::failure() const {
  if (ok()) return "";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", wall_seconds);
  const std::string how = timed_out ? "timed out after " + std::string(seconds) + " s"
                          : exit_code < 0 ? "did not run to its end"
                                          : "exited with status " + std::to_string(exit_code);
  const std::string tail = last_line(log);
  return builder + " " + how + (tail.empty() ? "" : ": " + tail);
}

std::vector<std::string> known_builders() {
  std::vector<std::string> names;
  for (const BuilderSpec& s : specs()) names.push_back(s.name);
  return names;
}

BuilderInstall find_builder(const std::string& builder) {
  const BuilderSpec& spec = spec_of(builder);
  BuilderInstall install{on_path(spec.name), ""};
  if (install.path.empty()) return install;
  BuilderRun banner;
  run_child(install.path, spec.version_arguments, 10, banner);
  std::istringstream lines(banner.log);
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find_first_not_of("* \t"), last = line.find_last_not_of("* \t\r");
    if (first != std::string::npos) {
      install.version = line.substr(first, last - first + 1);
      break;
    }
  }
  return install;
}

BuilderRun run_node_builder(const std::string& builder, const std::string& in_pwad, const std::string& out_pwad,
                            double timeout_s) {
  const BuilderSpec& spec = spec_of(builder);
  if (!std::ifstream(in_pwad)) throw InputError(in_pwad + ": cannot open the map's PWAD");
  BuilderRun run;
  run.builder = builder;
  run.output_path = out_pwad;
  run_child(spec.name, spec.arguments(in_pwad, out_pwad), timeout_s, run);
  return run;
}

void check_builder_name(const std::string& name) {
  const auto known = known_builders();
  if (std::find(known.begin(), known.end(), name) != known.end()) return;
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  throw UsageError("unknown node builder '" + name + "' (known: " + list + ")");
}

}  // namespace bsp::experiments
