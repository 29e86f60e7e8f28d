#pragma once
// A suite's jobs, in the one order every sweep, shard and journal agrees on.
#include <cstdint>
#include <string>
#include <string_view>

#include "experiments/job.h"
#include "suite/suite.h"

namespace bsp::suite {

// Every job of the suite, without repeats (jobs alike in Job::measured_identity are one run, the
// one of smallest size kept), largest sizes first (so a parallel run starts its long jobs early),
// ties broken by key.
experiments::Jobs expand(const Suite& suite);

struct Shard {
  std::uint32_t index = 0;  // 0-based
  std::uint32_t count = 1;
};
// Parses "i/N" with 0 <= i < N; throws UsageError otherwise.
Shard parse_shard(const std::string& text);
// The jobs shard `s` runs: every count-th job of the expanded order starting at index, which spreads
// sizes evenly over shards. Deterministic, and the shards partition the suite.
experiments::Jobs shard_jobs(const experiments::Jobs& jobs, Shard s);

// Hash of the suite's name, every job key and, for a suite file, its text: two reports come from the
// same suite definition exactly when these agree.
std::string definition_hash(const std::string& suite_name, const experiments::Jobs& jobs,
                            std::string_view source_text = {});

}  // namespace bsp::suite
