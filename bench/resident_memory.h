#pragma once
// The process's resident memory, from Linux's /proc/self/status, for measuring how much memory a
// build holds at its peak. Returns nullopt where /proc is not there: the counters are then left out,
// and the benchmark gate reports them missing against a baseline that has them.
#include <cstdint>
#include <optional>

namespace bsp::bench {

// Gives freed heap memory back to the system (malloc_trim), so memory the allocator merely kept
// from earlier work neither counts as resident nor hides what the next step allocates, then
// restarts the peak (VmHWM) at the current resident size (writing 5 to /proc/self/clear_refs).
// Returns the resident bytes after the trim.
std::optional<std::uint64_t> restart_peak();

// The most bytes resident since restart_peak() (VmHWM).
std::optional<std::uint64_t> peak_resident();

}  // namespace bsp::bench
