#pragma once
// The sweep journal: one JSON line per finished job, appended, flushed and fsynced before the next
// job is recorded, so an interrupted sweep (Ctrl-C, kill -9, power loss) loses at most the jobs that
// were still running. Rerunning the same command reads the journal and skips the recorded jobs.
//
// A kill during a write can leave the last line cut short: it is dropped (counted in torn_lines())
// and truncated away so the next append starts on a fresh line. A malformed line anywhere else is
// not an interruption but damage, reported as an InputError naming the file and line.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace bsp::sweep {

class Journal {
 public:
  // Creates the file and its directories when missing. Each record must be an object with a
  // string "key".
  explicit Journal(std::string path);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  const std::vector<nlohmann::json>& records() const { return records_; }
  std::uint64_t torn_lines() const { return torn_; }
  const std::string& path() const { return path_; }
  // Not thread-safe: callers serialise appends.
  void append(const nlohmann::json& record);

 private:
  void load();

  std::string path_;
  int fd_ = -1;
  std::vector<nlohmann::json> records_;
  std::uint64_t torn_ = 0;
};

}  // namespace bsp::sweep
