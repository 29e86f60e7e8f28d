#pragma once
// Notation used across src/experiments/:
//   kind   — a kind of experiment (draw, merge, animate, occlude, doom): one folder of its own,
//            holding its typed block and job, registered once (suite/kinds.cpp)
//   block  — one entry of a suite file under the kind's key, parsed and validated once (block.h)
//   job    — one run a block expands to: typed parameters, a key, an identity and a run function
//   record — what a job's run returns (analysis/SCHEMA.md): {key, id, metrics, invariants,
//            validation, ray_shooting, timings}
//
// A job's key is a hash of everything that determines its deterministic results, so journals,
// shards, merged reports and the regression gate all match runs by key. The sweep, the journal and
// the report know jobs only through this interface.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "experiments/timing.h"

namespace bsp::experiments {

// What a run is told besides its own parameters.
struct RunContext {
  std::optional<PlantedSlowdown> plant;  // TEST ONLY (timing.h)
  // The factor by which timed batches of the runs labelled `label` are slowed: 1 unless planted.
  double slowdown(const std::string& label) const { return plant && plant->heuristic == label ? plant->factor : 1.0; }
};

class Job {
 public:
  virtual ~Job() = default;
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  // The kind's name: "draw", "merge", "animate", "occlude" or "doom".
  virtual std::string_view kind() const = 0;
  // 16 hex digits (see the header comment).
  const std::string& key() const { return key_; }
  // The requested size: what orders a suite's jobs (largest first) and weighs them for the time
  // left; 0 when the job has none.
  std::uint64_t n() const { return n_; }
  // What the run measures, apart from its nominal size: two jobs alike in it are one run, and a
  // suite keeps the one of smallest n. The key, unless a kind knows better (a generator may make
  // the same scene at several sizes).
  virtual std::string measured_identity() const { return key_; }
  // {kind, scene, scene_params, heuristic, ..., command}: what reports and the gate show and group
  // by, with the command that repeats the run.
  virtual nlohmann::json identity() const = 0;
  // Runs the job and returns its record. Throws what the pieces throw (UsageError, InputError, or
  // a bug the runner reports as a failed job).
  virtual nlohmann::json run(const RunContext& context) const = 0;

 protected:
  Job() = default;
  // Called once by the kind's constructor, after its own fields are set.
  void set_identity(std::string key, std::uint64_t n) {
    key_ = std::move(key);
    n_ = n;
  }

 private:
  std::string key_;
  std::uint64_t n_ = 0;
};

using JobPtr = std::shared_ptr<const Job>;
using Jobs = std::vector<JobPtr>;

// The record's frame around a kind's sections: {key, id, metrics, invariants, validation,
// ray_shooting, timings}, with the job's wall time since `start_seconds` (a steady clock,
// wall_seconds()) in timings.job_seconds.
nlohmann::json make_record(const Job& job, nlohmann::json id, nlohmann::json metrics, nlohmann::json invariants,
                           nlohmann::json validation, nlohmann::json ray_shooting, nlohmann::json timings,
                           double start_seconds);
// Seconds on a steady clock, for make_record's start.
double wall_seconds();
// A double as a command line reads it back exactly (17 significant digits): the commands that
// repeat a job carry its settings so.
std::string exact_text(double x);

// A record field and where it stands in a stats struct's JSON (a JSON pointer into its to_json, the
// one place the struct becomes JSON), so a record takes its fields from there instead of copying
// the struct's members one at a time.
struct JsonField {
  const char* name;
  const char* pointer;
};
// Adds each field of `from` found at its pointer to `out` under its name.
void pick_fields(const nlohmann::json& from, std::span<const JsonField> fields, nlohmann::json& out);

}  // namespace bsp::experiments
