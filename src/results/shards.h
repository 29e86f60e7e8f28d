#pragma once
// Combining the reports of a sharded sweep (`--shard i/N` on several machines or processes) into
// the report the unsharded sweep would have written: same runs, same aggregates, one shard section
// per input.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace bsp::results {

struct NamedReport {
  std::string name;  // the file it came from, for messages
  nlohmann::json report;
};

// Throws InputError when the inputs are not shards of one suite definition (name and definition
// hash), when a shard appears twice or is missing, when shard counts disagree, or when a run
// appears in two inputs.
nlohmann::json combine_shards(const std::vector<NamedReport>& inputs);

}  // namespace bsp::results
