#include "resident_memory.h"

#include <malloc.h>

#include <fstream>
#include <string>

namespace bsp::bench {

namespace {

// A "Name:   N kB" line of /proc/self/status, in bytes.
std::optional<std::uint64_t> status_bytes(const std::string& name) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(name + ":", 0) == 0) return std::stoull(line.substr(name.size() + 1)) * 1024;
  return std::nullopt;
}

}  // namespace

std::optional<std::uint64_t> restart_peak() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  if (!(clear << "5" << std::flush)) return std::nullopt;
  return status_bytes("VmRSS");
}

std::optional<std::uint64_t> peak_resident() { return status_bytes("VmHWM"); }

}  // namespace bsp::bench
