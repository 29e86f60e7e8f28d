#pragma once
// Results over time: sweep reports kept in a SQLite database (`--history FILE.sqlite`), one row per
// appended report, keyed by suite, machine fingerprint and git revision, with the sweep's
// calibration beside it (not part of the key). The regression gate judges a report against the
// last k of the same suite and machine (regress --history), and `bspbench history` draws every
// gated timing group and metric over the rows (history_page.h).
//
// The database holds whole reports (as JSON text), so anything a report says can be asked again;
// a quick-suite report takes about 10 MB. Appends are single transactions: a failed append leaves the
// database as it was. Schema: docs/history.md.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

struct sqlite3;

namespace bsp::history {

// How many earlier entries judge a run (regress --history, the page): the default and the most.
inline constexpr std::size_t kDefaultLast = 5;
inline constexpr std::size_t kMaxLast = 100;

// What identifies a machine for timing comparisons: its processor, core count, compiler and flags
// (a report's environment). Timings of different machines are never compared.
struct Machine {
  std::string fingerprint;  // 16 hex digits of the fields below
  std::string cpu_model, compiler, flags;
  std::uint64_t hardware_threads = 0;
};
Machine machine_of(const nlohmann::json& report);

// One appended report, without the report itself.
struct Entry {
  std::int64_t id = 0;  // increasing in the order of appends
  std::string suite, definition_hash, revision, date_utc;
  Machine machine;
  double calibration_seconds = 0;
  std::uint64_t runs = 0, failures = 0;
  std::string report_hash;  // 16 hex digits of the report's JSON: finds a report appended already
};

class Database {
 public:
  // Opens the database at `path`: for appending, created when missing (`create`), else read-only.
  // Throws InputError naming the file for one that is not a SQLite database, not bspbench's, of
  // another schema version, or cannot be opened, read or (when appending) written.
  static Database open(const std::string& path, bool create);
  ~Database();
  Database(Database&&) noexcept;
  Database& operator=(Database&&) noexcept;

  // Appends sweep or merge-reports reports in one transaction (one shard of several is refused:
  // append the merged report); returns their entries. Throws InputError, appending none, when one
  // is not such a report.
  std::vector<Entry> append(std::span<const nlohmann::json> reports);
  // Every entry, oldest first; of one suite when `suite` is given.
  std::vector<Entry> entries(const std::optional<std::string>& suite = std::nullopt) const;
  // The last `k` entries of `suite` on machine `fingerprint` appended before entry `before` (or
  // before every entry when none), oldest first.
  std::vector<Entry> last(const std::string& suite, const std::string& fingerprint, std::size_t k,
                          std::optional<std::int64_t> before = std::nullopt) const;
  // The report of an entry.
  nlohmann::json report(std::int64_t id) const;
  // The first entry holding this very report, if it was appended.
  std::optional<std::int64_t> find(const nlohmann::json& report) const;
  const std::string& path() const { return path_; }

 private:
  Database(std::string path, sqlite3* db) : path_(std::move(path)), db_(db) {}
  std::string path_;
  sqlite3* db_ = nullptr;
};

}  // namespace bsp::history
