#pragma once
// Progress of a sweep on stderr: done/total, rate, time left. On a terminal one line is rewritten in
// place after every job; otherwise (CI logs, files) a plain line is printed at most every
// kPlainInterval, plus a final one. Time left is estimated from job weights (a job's weight is its
// expected cost), not job counts, because sizes span orders of magnitude.
#include <chrono>
#include <cstdint>
#include <iosfwd>

namespace bsp::sweep {

class Progress {
 public:
  static constexpr std::chrono::seconds kPlainInterval{10};

  Progress(std::ostream& out, bool terminal, std::uint64_t total_jobs, double total_weight);
  // Called once per finished job, from one thread at a time.
  void job_done(double weight);
  // Prints the final line.
  void finish();

 private:
  void print(bool final_line);

  std::ostream& out_;
  bool terminal_;
  std::uint64_t total_, done_ = 0;
  double total_weight_, done_weight_ = 0;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace bsp::sweep
