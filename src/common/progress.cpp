#include "common/progress.h"

#include <cstdio>
#include <ostream>
#include <string>
#include <utility>

namespace bsp {

namespace {

std::string clock_text(double seconds) {
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  return buf;
}

}  // namespace

Progress::Progress(std::ostream& out, bool terminal, std::string label, std::string unit, std::uint64_t total_items,
                   double total_weight)
    : out_(out), terminal_(terminal), label_(std::move(label)), unit_(std::move(unit)), total_(total_items),
      total_weight_(total_weight),
      start_(std::chrono::steady_clock::now()), last_print_(start_) {}

void Progress::job_done(double weight, std::string_view detail) {
  ++done_;
  done_weight_ += weight;
  detail_ = detail;
  if (terminal_ || std::chrono::steady_clock::now() - last_print_ >= kPlainInterval) print(false);
}

void Progress::finish() { print(true); }

void Progress::print(bool final_line) {
  last_print_ = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(last_print_ - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0.0;
  const double fraction = total_weight_ > 0 ? done_weight_ / total_weight_ : 1.0;
  const bool known = total_ != kUnknownTotal;
  std::string line = label_ + ": " + std::to_string(done_);
  if (known) line.append("/").append(std::to_string(total_));
  line.append(" ").append(unit_);
  char buf[96];
  std::snprintf(buf, sizeof buf, ", %.2f %s/s, elapsed %s", rate, unit_.c_str(), clock_text(elapsed).c_str());
  line += buf;
  if (!final_line && fraction > 0 && fraction < 1)
    line += (known ? ", about " : ", at most ") + clock_text(elapsed * (1 - fraction) / fraction) + " left";
  if (!detail_.empty()) line += ", " + detail_;
  if (terminal_) out_ << "\r\033[K" << line << (final_line ? "\n" : "") << std::flush;
  else out_ << line << "\n" << std::flush;
}

}  // namespace bsp
