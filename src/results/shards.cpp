#include "results/shards.h"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "common/errors.h"
#include "results/report.h"

namespace bsp::results {

namespace {

void check_same_suite(const std::vector<NamedReport>& inputs) {
  const auto& first = inputs.front().report["suite"];
  for (const auto& in : inputs) {
    const auto& s = in.report["suite"];
    if (s["name"] != first["name"] || s["definition_hash"] != first["definition_hash"])
      throw InputError(in.name + ": suite " + s["name"].get<std::string>() + " (definition " +
                       s["definition_hash"].get<std::string>() + ") differs from " + inputs.front().name + "'s " +
                       first["name"].get<std::string>() + " (definition " +
                       first["definition_hash"].get<std::string>() + "); merge shards of one sweep only");
  }
}

// Every shard index of 0..count-1 exactly once.
nlohmann::json collect_shards(const std::vector<NamedReport>& inputs) {
  std::map<std::uint64_t, std::string> seen;
  std::uint64_t count = 0;
  nlohmann::json shards = nlohmann::json::array();
  for (const auto& in : inputs)
    for (const auto& s : in.report["shards"]) {
      const auto index = s["index"].get<std::uint64_t>(), c = s["count"].get<std::uint64_t>();
      if (count == 0) count = c;
      if (c != count)
        throw InputError(in.name + ": shard " + std::to_string(index) + "/" + std::to_string(c) +
                         " does not match the other inputs' " + std::to_string(count) + " shards");
      if (!seen.emplace(index, in.name).second)
        throw InputError("shard " + std::to_string(index) + "/" + std::to_string(count) + " given twice (" +
                         seen[index] + " and " + in.name + ")");
      shards.push_back(s);
    }
  std::string missing;
  for (std::uint64_t i = 0; i < count; ++i)
    if (!seen.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(count);
  if (!missing.empty()) throw InputError("missing shard(s) " + missing);
  std::sort(shards.begin(), shards.end(),
            [](const nlohmann::json& a, const nlohmann::json& b) { return a["index"] < b["index"]; });
  return shards;
}

// The union of the inputs' records under `section`; a key in two inputs is an error.
nlohmann::json collect(const std::vector<NamedReport>& inputs, const char* section) {
  std::map<std::string, std::string> seen;
  nlohmann::json out = nlohmann::json::array();
  for (const auto& in : inputs)
    for (const auto& r : in.report[section]) {
      const std::string key = r["key"].get<std::string>();
      if (!seen.emplace(key, in.name).second)
        throw InputError("job " + key + " appears in both " + seen[key] + " and " + in.name);
      out.push_back(r);
    }
  return out;
}

}  // namespace

nlohmann::json combine_shards(const std::vector<NamedReport>& inputs) {
  if (inputs.empty()) throw UsageError("no reports to merge");
  check_same_suite(inputs);
  nlohmann::json shards = collect_shards(inputs);
  nlohmann::json runs = collect(inputs, "runs");
  nlohmann::json failures = collect(inputs, "failures");
  return assemble_report(inputs.front().report["suite"], std::move(shards), std::move(runs), std::move(failures));
}

}  // namespace bsp::results
