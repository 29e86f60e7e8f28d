#pragma once
// What `bspbench history` draws, computed from a history database (history.h) for
// analysis/history.py: per suite, its entries oldest first with the gate's decision on each (the
// entry judged against the last k entries of its suite and machine before it, as regress --history
// judges), and per timing group its series: the gated build time (each run's median sample over its
// in-run reference, geometric mean over the group's runs) and the sum over its runs of every
// numeric metric. The layout: docs/history.md.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "history/history.h"

namespace bsp::history {

struct PageSettings {
  std::size_t last = kDefaultLast;  // k: how many earlier entries of the same suite and machine judge an entry
  std::optional<std::string> suite;  // only this suite
  // Called after each entry is read and judged (done of total, every suite's entries counted), when
  // set: the CLI's progress line. An entry's weight is its runs.
  std::function<void(std::uint64_t runs)> on_entry;
};

// Throws InputError when the database holds no entry (of the suite).
nlohmann::json page_data(const Database& db, const PageSettings& settings);

}  // namespace bsp::history
