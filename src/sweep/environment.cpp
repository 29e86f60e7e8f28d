#include "sweep/environment.h"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <thread>

#include "common/hash.h"
#include "common/revision.h"
#include "experiments/plugin_loader.h"

namespace bsp::sweep {

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string compiler() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#else
  return std::string("gcc ") + __VERSION__;
#endif
}

std::string host_name() {
  char buf[256] = {};
  return ::gethostname(buf, sizeof buf - 1) == 0 ? buf : "unknown";
}

}  // namespace

nlohmann::json environment_json(int threads) {
  nlohmann::json env{{"git_revision", git_revision()},
          {"compiler", compiler()},
          {"build_type", BSPBENCH_BUILD_TYPE},
          {"flags", BSPBENCH_CXX_FLAGS},
          {"cpu_model", cpu_model()},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"threads", threads},
          {"host", host_name()},
          {"date_utc", utc_now()}};
  // The plugins loaded (--plugin, a suite's "plugins"), when any: what else made the results.
  for (const PluginIdentity& p : experiments::loaded_plugins())
    env["plugins"].push_back({{"name", p.name}, {"version", p.version}, {"hash", p.hash}, {"path", p.path}});
  return env;
}

std::string executable_hash() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  Hasher h;
  h.add_string(bytes);
  return h.hex();
}

}  // namespace bsp::sweep
