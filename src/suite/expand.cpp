#include "suite/expand.h"

#include <algorithm>
#include <charconv>
#include <set>

#include "common/errors.h"
#include "common/hash.h"

namespace bsp::suite {

experiments::Jobs expand(const Suite& suite) {
  experiments::Jobs all;
  for (const auto& b : suite.blocks) {
    experiments::Jobs more = b.block->expand();
    all.insert(all.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
  }
  // Smallest nominal size first, so a scene built at several sizes runs once, at the smallest.
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a->n() < b->n(); });
  experiments::Jobs jobs;
  std::set<std::string> seen;
  for (auto& j : all)
    if (seen.insert(j->measured_identity()).second) jobs.push_back(std::move(j));
  std::sort(jobs.begin(), jobs.end(), [](const auto& a, const auto& b) {
    return a->n() != b->n() ? a->n() > b->n() : a->key() < b->key();
  });
  return jobs;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  const auto parse = [&](std::string_view part, std::uint32_t& v) {
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    return ec == std::errc() && ptr == part.data() + part.size() && !part.empty();
  };
  const std::string_view all(text);
  if (slash == std::string::npos || !parse(all.substr(0, slash), s.index) || !parse(all.substr(slash + 1), s.count) ||
      s.count == 0 || s.index >= s.count)
    throw UsageError("--shard wants i/N with 0 <= i < N, not '" + text + "'");
  return s;
}

experiments::Jobs shard_jobs(const experiments::Jobs& jobs, Shard s) {
  experiments::Jobs out;
  for (std::size_t i = s.index; i < jobs.size(); i += s.count) out.push_back(jobs[i]);
  return out;
}

std::string definition_hash(const std::string& suite_name, const experiments::Jobs& jobs, std::string_view source_text) {
  Hasher h;
  h.add_string(suite_name);
  h.add_u64(jobs.size());
  for (const auto& j : jobs) h.add_string(j->key());
  if (!source_text.empty()) h.add_string(source_text);
  return h.hex();
}

}  // namespace bsp::suite
