#include "sweep/runner.h"

#include <omp.h>

#include <atomic>
#include <exception>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

#include "common/errors.h"
#include "common/hash.h"
#include "sweep/calibration.h"
#include "sweep/environment.h"
#include "sweep/journal.h"
#include "common/progress.h"
#include "results/report.h"

namespace bsp::sweep {

namespace {

// Expected cost of a job for the time-left estimate; the constant keeps tiny jobs from counting
// as free (they pay for scene generation and Embree setup).
constexpr double kJobOverheadPolygons = 200;

double weight(const experiments::Job& j) { return static_cast<double>(j.n()) + kJobOverheadPolygons; }

struct Work {
  experiments::Jobs assigned, pending;
  nlohmann::json runs = nlohmann::json::array();
  nlohmann::json failures = nlohmann::json::array();
};

// Takes the journaled runs of assigned jobs; the rest are pending.
void resume(const Journal& journal, Work& w) {
  std::map<std::string, const nlohmann::json*> done;
  for (const auto& r : journal.records()) done[r["key"].get<std::string>()] = &r;
  for (const auto& job : w.assigned) {
    const auto it = done.find(job->key());
    if (it != done.end()) w.runs.push_back(*it->second);
    else w.pending.push_back(job);
  }
}

void run_pending(Work& w, Journal& journal, double calibration, int threads, const experiments::RunContext& context,
                 Progress* progress) {
  // The journal failed (results could no longer be kept), or a plugin threw (its other jobs
  // would too): the sweep starts no more jobs and rethrows it. After a plugin's fault, jobs still
  // running are journaled when they end, so a rerun resumes them.
  std::exception_ptr fatal;
  std::atomic<bool> stop{false};
  bool journal_failed = false;
  const auto count = static_cast<std::int64_t>(w.pending.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t i = 0; i < count; ++i) {
    if (stop) continue;
    const experiments::Job& job = *w.pending[static_cast<std::size_t>(i)];
    // Parallel regions inside a job get one thread whatever --threads is, so a job's timings mean
    // the same in every sweep (this sets the ICV of this thread's task only).
    omp_set_num_threads(1);
    nlohmann::json record;
    std::optional<std::string> error;
    try {
      record = job.run(context);
      record["calibration_seconds"] = calibration;
    } catch (const PluginError&) {
#pragma omp critical(bspbench_sweep_journal)
      if (!fatal) fatal = std::current_exception();
      stop = true;
      continue;
    } catch (const std::exception& e) {
      error = e.what();
    } catch (...) {
      error = "unknown exception";
    }
#pragma omp critical(bspbench_sweep_journal)
    {
      if (error) {
        w.failures.push_back({{"key", job.key()}, {"id", job.identity()}, {"error", *error}});
      } else if (!journal_failed) {
        try {
          journal.append(record);
          w.runs.push_back(std::move(record));
        } catch (...) {
          if (!fatal) fatal = std::current_exception();
          stop = journal_failed = true;
        }
      }
      if (progress) progress->job_done(weight(job));
    }
  }
  if (fatal) std::rethrow_exception(fatal);
}

}  // namespace

std::string journal_path(const suite::Suite& suite, const SweepOptions& options) {
  const auto jobs = suite::expand(suite);
  std::string name = suite.name + "-" + suite::definition_hash(suite.name, jobs, suite.source.text) + "-" + executable_hash();
  if (options.shard) name += "-shard" + std::to_string(options.shard->index) + "of" + std::to_string(options.shard->count);
  // A planted run must never resume from an honest journal, nor the other way round.
  if (options.plant) name += "-planted-" + options.plant->heuristic + "-x" + std::to_string(options.plant->factor);
  return (std::filesystem::path(options.journal_dir) / (name + ".jsonl")).string();
}

nlohmann::json run_sweep(const suite::Suite& suite, const SweepOptions& options) {
  const experiments::Jobs jobs = suite::expand(suite);
  const suite::Shard shard = options.shard.value_or(suite::Shard{});
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  Work w;
  w.assigned = suite::shard_jobs(jobs, shard);
  const std::string path = journal_path(suite, options);
  if (options.fresh) {
    std::error_code ec;  // a journal that is not there is already discarded
    std::filesystem::remove(path, ec);
  }
  Journal journal(path);
  resume(journal, w);
  const Calibration calibration = calibrate();
  if (options.log)
    *options.log << "sweep " << suite.name << ": " << w.assigned.size() << " jobs, " << w.runs.size()
                 << " already in " << path << (journal.torn_lines() ? " (dropped a torn last line)" : "")
                 << ", " << threads << " threads, calibration " << calibration.seconds << " s\n";
  double total_weight = 0;
  for (const auto& j : w.pending) total_weight += weight(*j);
  std::optional<Progress> progress;
  if (options.log) progress.emplace(*options.log, options.log_is_terminal, "sweep", "jobs", w.pending.size(), total_weight);
  run_pending(w, journal, calibration.seconds, threads, experiments::RunContext{options.plant},
              progress ? &*progress : nullptr);
  if (progress) progress->finish();
  nlohmann::json shard_section{{"index", shard.index},       {"count", shard.count},
                               {"jobs", w.assigned.size()},  {"environment", environment_json(threads)},
                               {"calibration", to_json(calibration)}, {"journal", path}};
  if (options.plant)
    shard_section["planted_slowdown"] = {{"heuristic", options.plant->heuristic}, {"factor", options.plant->factor}};
  nlohmann::json suite_json{{"name", suite.name}, {"definition_hash", suite::definition_hash(suite.name, jobs, suite.source.text)},
                            {"jobs", jobs.size()}};
  if (!suite.source.text.empty()) {
    Hasher text_hash;
    text_hash.add_string(suite.source.text);
    suite_json["source"] = {{"path", suite.source.path}, {"hash", text_hash.hex()}, {"text", suite.source.text}};
  }
  return results::assemble_report(std::move(suite_json), nlohmann::json::array({std::move(shard_section)}), std::move(w.runs),
                         std::move(w.failures));
}

}  // namespace bsp::sweep
