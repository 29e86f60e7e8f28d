#include "history/history.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/hash.h"

namespace bsp::history {

namespace {

// PRAGMA application_id of bspbench's databases ("bspb"), and the schema version (user_version).
constexpr std::int64_t kApplicationId = 0x62737062;
constexpr std::int64_t kSchemaVersion = 1;
// How long an append waits for another process's (a parallel CI job's) to finish.
constexpr int kBusyMilliseconds = 10000;

constexpr const char* kSchema = R"(
  CREATE TABLE machines(fingerprint TEXT PRIMARY KEY, cpu_model TEXT NOT NULL,
                        hardware_threads INTEGER NOT NULL, compiler TEXT NOT NULL, flags TEXT NOT NULL);
  CREATE TABLE sweeps(id INTEGER PRIMARY KEY AUTOINCREMENT, suite TEXT NOT NULL,
                      machine TEXT NOT NULL REFERENCES machines(fingerprint), revision TEXT NOT NULL,
                      definition_hash TEXT NOT NULL, date_utc TEXT NOT NULL, calibration_seconds REAL NOT NULL,
                      runs INTEGER NOT NULL, failures INTEGER NOT NULL, report_hash TEXT NOT NULL,
                      report TEXT NOT NULL);
  CREATE INDEX sweeps_series ON sweeps(suite, machine, id);
  CREATE INDEX sweeps_report ON sweeps(report_hash);
)";

// A prepared statement, finalized when it goes out of scope.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const char* sql) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) != SQLITE_OK) fail();
  }
  ~Statement() { sqlite3_finalize(s_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& v) {
    check(sqlite3_bind_text(s_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind(int i, std::int64_t v) {
    check(sqlite3_bind_int64(s_, i, v));
    return *this;
  }
  Statement& bind(int i, double v) {
    check(sqlite3_bind_double(s_, i, v));
    return *this;
  }
  // True while a row is ready; false when done.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE) fail();
    return false;
  }
  std::string text(int column) const {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(s_, column));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(s_, column))) : std::string();
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(s_, column); }
  sqlite3_stmt* handle() const { return s_; }
  double real(int column) const { return sqlite3_column_double(s_, column); }

 private:
  void check(int rc) const {
    if (rc != SQLITE_OK) fail();
  }
  [[noreturn]] void fail() const { throw InputError(path_ + ": " + sqlite3_errmsg(db_)); }

  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* s_ = nullptr;
};

void execute(sqlite3* db, const std::string& path, const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string what = message ? message : sqlite3_errmsg(db);
    sqlite3_free(message);
    throw InputError(path + ": " + what);
  }
}

std::int64_t pragma(sqlite3* db, const std::string& path, const char* sql) {
  Statement s(db, path, sql);
  return s.step() ? s.integer(0) : 0;
}

// Checks a database bspbench opened, or gives an empty new one the schema.
void check_or_create(sqlite3* db, const std::string& path, bool create) {
  const std::int64_t id = pragma(db, path, "PRAGMA application_id");  // fails on a file that is no database
  const std::int64_t tables = pragma(db, path, "SELECT count(*) FROM sqlite_schema");
  if (id == 0 && tables == 0) {
    if (!create) throw InputError(path + ": an empty database, not a bspbench history");
    execute(db, path, "BEGIN IMMEDIATE");
    // Another process may have made it between the look and the lock.
    if (pragma(db, path, "SELECT count(*) FROM sqlite_schema") > 0) {
      execute(db, path, "COMMIT");
      return check_or_create(db, path, false);
    }
    execute(db, path, kSchema);
    execute(db, path, ("PRAGMA application_id = " + std::to_string(kApplicationId)).c_str());
    execute(db, path, ("PRAGMA user_version = " + std::to_string(kSchemaVersion)).c_str());
    execute(db, path, "COMMIT");
    return;
  }
  if (id != kApplicationId) throw InputError(path + ": a SQLite database, but not a bspbench history");
  const std::int64_t version = pragma(db, path, "PRAGMA user_version");
  if (version != kSchemaVersion)
    throw InputError(path + ": a bspbench history of schema version " + std::to_string(version) + "; this bspbench reads version " +
                     std::to_string(kSchemaVersion));
}

const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& what) {
  if (!j.is_object() || !j.contains(key)) throw InputError(what + ": no '" + key + "'");
  return j[key];
}

Entry read_entry(const Statement& s) {
  Entry e;
  e.id = s.integer(0);
  e.suite = s.text(1);
  e.machine.fingerprint = s.text(2);
  e.revision = s.text(3);
  e.definition_hash = s.text(4);
  e.date_utc = s.text(5);
  e.calibration_seconds = s.real(6);
  e.runs = static_cast<std::uint64_t>(s.integer(7));
  e.failures = static_cast<std::uint64_t>(s.integer(8));
  e.machine.cpu_model = s.text(9);
  e.machine.hardware_threads = static_cast<std::uint64_t>(s.integer(10));
  e.machine.compiler = s.text(11);
  e.machine.flags = s.text(12);
  e.report_hash = s.text(13);
  return e;
}

constexpr const char* kEntryColumns =
    "SELECT s.id, s.suite, s.machine, s.revision, s.definition_hash, s.date_utc, s.calibration_seconds, s.runs, "
    "s.failures, m.cpu_model, m.hardware_threads, m.compiler, m.flags, s.report_hash "
    "FROM sweeps s JOIN machines m ON m.fingerprint = s.machine ";

std::string json_hash(const std::string& text) {
  Hasher h;
  h.add_string(text);
  return h.hex();
}

}  // namespace

Machine machine_of(const nlohmann::json& report) {
  const nlohmann::json& shards = field(report, "shards", "report");
  if (!shards.is_array() || shards.empty()) throw InputError("report: no shards");
  const nlohmann::json& env = field(shards[0], "environment", "report shard");
  Machine m;
  m.cpu_model = env.value("cpu_model", "");
  m.compiler = env.value("compiler", "");
  m.flags = env.value("flags", "");
  m.hardware_threads = env.value("hardware_threads", std::uint64_t{0});
  Hasher h;
  h.add_string(m.cpu_model);
  h.add_u64(m.hardware_threads);
  h.add_string(m.compiler);
  h.add_string(m.flags);
  m.fingerprint = h.hex();
  return m;
}

Database Database::open(const std::string& path, bool create) {
  std::error_code ec;
  if (!create && !std::filesystem::exists(path, ec)) throw InputError(path + ": no such history database");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": a directory, not a history database");
  sqlite3* db = nullptr;
  const int flags = create ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
  if (sqlite3_open_v2(path.c_str(), &db, flags, nullptr) != SQLITE_OK) {
    const std::string what = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw InputError(path + ": cannot open: " + what);
  }
  Database out(path, db);
  sqlite3_busy_timeout(db, kBusyMilliseconds);
  check_or_create(db, out.path_, create);
  return out;
}

Database::~Database() { sqlite3_close(db_); }
Database::Database(Database&& o) noexcept : path_(std::move(o.path_)), db_(std::exchange(o.db_, nullptr)) {}
Database& Database::operator=(Database&& o) noexcept {
  std::swap(path_, o.path_);
  std::swap(db_, o.db_);
  return *this;
}

namespace {

// The entry a report will be (id 0); throws InputError when it is none to append.
Entry entry_of(const nlohmann::json& report, const std::string& what) try {
  const nlohmann::json& suite = field(report, "suite", what);
  const nlohmann::json& shards = field(report, "shards", what);
  if (!shards.is_array() || shards.empty()) throw InputError(what + ": no shards");
  const std::uint64_t count = shards[0].value("count", std::uint64_t{1});
  if (shards.size() < count)
    throw InputError(what + ": one shard of " + std::to_string(count) + "; append the report of merge-reports instead");
  const nlohmann::json& env = field(shards[0], "environment", what);
  Entry e;
  e.suite = field(suite, "name", what).get<std::string>();
  e.definition_hash = suite.value("definition_hash", "");
  e.revision = env.value("git_revision", "unknown");
  e.date_utc = env.value("date_utc", "");
  e.calibration_seconds = shards[0].value("calibration", nlohmann::json::object()).value("seconds", 0.0);
  e.runs = field(report, "runs", what).size();
  e.failures = report.value("failures", nlohmann::json::array()).size();
  e.machine = machine_of(report);
  return e;
} catch (const nlohmann::json::exception& x) {  // a field of the wrong type
  throw InputError(what + ": " + x.what());
}

}  // namespace

std::vector<Entry> Database::append(std::span<const nlohmann::json> reports) {
  std::vector<Entry> out;
  std::vector<std::string> texts;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    out.push_back(entry_of(reports[i], "report " + std::to_string(i + 1) + " to append to " + path_));
    texts.push_back(reports[i].dump());
    out.back().report_hash = json_hash(texts.back());
  }
  if (reports.empty()) return out;
  execute(db_, path_, "BEGIN IMMEDIATE");
  try {
    for (std::size_t i = 0; i < reports.size(); ++i) {
      Entry& e = out[i];
      Statement(db_, path_, "INSERT OR IGNORE INTO machines VALUES (?1, ?2, ?3, ?4, ?5)")
          .bind(1, e.machine.fingerprint).bind(2, e.machine.cpu_model)
          .bind(3, static_cast<std::int64_t>(e.machine.hardware_threads)).bind(4, e.machine.compiler)
          .bind(5, e.machine.flags).step();
      Statement(db_, path_,
                "INSERT INTO sweeps(suite, machine, revision, definition_hash, date_utc, calibration_seconds, runs, "
                "failures, report_hash, report) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)")
          .bind(1, e.suite).bind(2, e.machine.fingerprint).bind(3, e.revision).bind(4, e.definition_hash)
          .bind(5, e.date_utc).bind(6, e.calibration_seconds).bind(7, static_cast<std::int64_t>(e.runs))
          .bind(8, static_cast<std::int64_t>(e.failures)).bind(9, e.report_hash).bind(10, texts[i]).step();
      e.id = sqlite3_last_insert_rowid(db_);
    }
    execute(db_, path_, "COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  return out;
}

std::vector<Entry> Database::entries(const std::optional<std::string>& suite) const {
  const std::string sql = std::string(kEntryColumns) + (suite ? "WHERE s.suite = ?1 " : "") + "ORDER BY s.id";
  Statement s(db_, path_, sql.c_str());
  if (suite) s.bind(1, *suite);
  std::vector<Entry> out;
  while (s.step()) out.push_back(read_entry(s));
  return out;
}

std::vector<Entry> Database::last(const std::string& suite, const std::string& fingerprint, std::size_t k,
                                  std::optional<std::int64_t> before) const {
  const std::string sql = std::string(kEntryColumns) +
                          "WHERE s.suite = ?1 AND s.machine = ?2 AND s.id < ?3 ORDER BY s.id DESC LIMIT ?4";
  Statement s(db_, path_, sql.c_str());
  s.bind(1, suite).bind(2, fingerprint).bind(3, before.value_or(INT64_MAX)).bind(4, static_cast<std::int64_t>(k));
  std::vector<Entry> out;
  while (s.step()) out.push_back(read_entry(s));
  std::reverse(out.begin(), out.end());
  return out;
}

std::optional<std::int64_t> Database::find(const nlohmann::json& report) const {
  Statement s(db_, path_, "SELECT min(id) FROM sweeps WHERE report_hash = ?1");
  s.bind(1, json_hash(report.dump()));
  if (!s.step() || sqlite3_column_type(s.handle(), 0) == SQLITE_NULL) return std::nullopt;
  return s.integer(0);
}

nlohmann::json Database::report(std::int64_t id) const {
  Statement s(db_, path_, "SELECT report FROM sweeps WHERE id = ?1");
  s.bind(1, id);
  if (!s.step()) throw InputError(path_ + ": no entry " + std::to_string(id));
  nlohmann::json j = nlohmann::json::parse(s.text(0), nullptr, false);
  if (j.is_discarded()) throw InputError(path_ + ": entry " + std::to_string(id) + " holds no JSON report");
  return j;
}

}  // namespace bsp::history
