#pragma once
// Progress of long work on stderr ("sweep: 12/400 jobs, ..."): done/total, rate, time left. On a
// terminal one line is rewritten in place after every item; otherwise (CI logs, files) a plain line
// is printed at most every kPlainInterval, plus a final one. Time left is estimated from the items'
// weights (an item's weight is its expected cost), not their count, because sizes span orders of
// magnitude. Work of unknown length under a budget (a search until proved or out of time) counts
// items without a total and weighs them by the seconds they took against the budget, so its time
// left is an upper bound ("at most").
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>

namespace bsp {

class Progress {
 public:
  static constexpr std::chrono::seconds kPlainInterval{10};

  // `label` starts each line (the command), `unit` names the items ("jobs", "runs").
  Progress(std::ostream& out, bool terminal, std::string label, std::string unit, std::uint64_t total_items,
           double total_weight);
  // Called once per finished item, from one thread at a time; `detail` ends the line (a search's
  // bounds, say).
  void job_done(double weight, std::string_view detail = {});
  // A total of 0 items: an unknown number, shown without "/total"; the time left is then the
  // budget's rest, "at most".
  static constexpr std::uint64_t kUnknownTotal = 0;
  // Prints the final line.
  void finish();

 private:
  void print(bool final_line);

  std::ostream& out_;
  bool terminal_;
  std::string label_, unit_;
  std::uint64_t total_, done_ = 0;
  double total_weight_, done_weight_ = 0;
  std::string detail_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace bsp
