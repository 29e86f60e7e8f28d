#pragma once
// Where a report was made: revision, compiler and flags, CPU, threads, date, host.
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace bsp::sweep {

// `threads` is the OpenMP thread count the sweep ran with.
nlohmann::json environment_json(int threads);

// FNV-1a of this program's own executable file: a journal written by one build is never resumed by
// another, whose results could differ even at the same git revision (uncommitted edits).
std::string executable_hash();

}  // namespace bsp::sweep
