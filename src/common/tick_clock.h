#pragma once
// Billing many short spans inside one long one: the build's time inside Splitter::choose is a few
// microseconds a node over a million nodes. Reading std::chrono::steady_clock costs a vDSO call
// (50-100 ns in a VM: 2% of a crystal build of 10^6 polygons, timing every choose); reading the
// processor's time-stamp counter costs a few nanoseconds. A TickBill counts ticks in the short spans
// and turns them into seconds once, at the end, as their share of the long span's steady_clock time,
// so no tick rate is assumed, only that it is constant over the span (x86-64's invariant TSC;
// elsewhere the ticks are steady_clock's own).
#include <algorithm>
#include <chrono>
#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__)
#include <x86intrin.h>
#endif

namespace bsp {

inline std::uint64_t read_ticks() {
#if defined(__x86_64__) && defined(__GNUC__)
  return __rdtsc();
#else
  return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

// The ticks from `start` to now, 0 if the counter reads lower than at the start (a thread moved to a
// core whose counter is behind, where counters are not synchronised): a span is never negative.
inline std::uint64_t ticks_since(std::uint64_t start) {
  const std::uint64_t now = read_ticks();
  return now > start ? now - start : 0;
}

// The long span, from construction to close(). Short spans inside it are read with read_ticks() and
// ticks_since().
class TickBill {
 public:
  TickBill() : start_(std::chrono::steady_clock::now()), start_ticks_(read_ticks()) {}
  // Ends the span; returns its steady_clock seconds.
  double close() {
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    ticks_ = ticks_since(start_ticks_);
    return seconds_;
  }
  // After close(): the seconds of `ticks` counted inside the span, as their share of it (at most all).
  double seconds_of(std::uint64_t ticks) const {
    return ticks_ == 0 ? 0.0 : seconds_ * static_cast<double>(std::min(ticks, ticks_)) / static_cast<double>(ticks_);
  }

 private:
  std::chrono::steady_clock::time_point start_;
  std::uint64_t start_ticks_;
  double seconds_ = 0.0;
  std::uint64_t ticks_ = 0;
};

}  // namespace bsp
