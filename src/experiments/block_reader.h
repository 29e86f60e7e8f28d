#pragma once
// Reading one block of a suite file (analysis/SUITE_SCHEMA.md): the checks every kind's block
// parser shares, each failing with one line, "FILE: JSON.PATH: problem" (an InputError), so a
// suite is refused whole before anything runs. Unknown keys, wrong types, empty lists and repeated
// entries are errors; names are checked against the registries.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "common/params.h"

namespace bsp {
struct GeneratorInfo;
enum class Kernel : std::uint8_t;  // tree/exact_build.h
}

namespace bsp::experiments {

// The bounds the CLI puts on the same settings, so a suite file asks nothing the commands refuse.
inline constexpr std::uint64_t kMaxViews = 1000;
inline constexpr std::uint64_t kMaxSeed = 9'000'000'000'000'000;

std::string child(const std::string& path, std::string_view key);
std::string element(const std::string& path, std::size_t i);
std::string join(const std::vector<std::string>& items);

class BlockReader {
 public:
  using json = nlohmann::json;
  // `file` names the suite in messages; `dir` is where its relative file scenes are found.
  BlockReader(std::string file, std::filesystem::path dir) : file_(std::move(file)), dir_(std::move(dir)) {}

  const std::filesystem::path& dir() const { return dir_; }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const;

  // Runs `f` and turns what the registries throw into a message at `path`.
  template <class F>
  auto at(const std::string& path, F&& f) const -> decltype(f()) {
    try {
      return f();
    } catch (const UsageError& e) {
      fail(path, e.what());
    } catch (const InputError& e) {
      fail(path, e.what());
    }
  }

  void expect(const json& j, bool ok, const std::string& path, const char* noun) const;
  void check_keys(const json& object, const std::string& path, std::initializer_list<std::string_view> known) const;
  static const json* optional(const json& object, const char* key);
  const json& required(const json& object, const std::string& path, const char* key) const;

  std::string string(const json& j, const std::string& path) const;
  bool boolean(const json& j, const std::string& path) const;
  std::uint64_t integer(const json& j, const std::string& path, std::uint64_t min, std::uint64_t max) const;
  // In [min, max], or (min, max] when open_min.
  double real(const json& j, const std::string& path, double min, double max, bool open_min = false) const;

  // A non-empty array, each element given to f with its path.
  void each(const json& j, const std::string& path, std::string_view if_empty,
            const std::function<void(const json&, const std::string&)>& f) const;
  // Remembers `identity` of the element at `path`; a second element with the same identity is an error.
  void once(std::map<std::string, std::string>& seen, const std::string& identity, const std::string& path) const;

  std::vector<std::uint64_t> integers(const json& j, const std::string& path, std::uint64_t min, std::uint64_t max,
                                      std::string_view if_empty) const;
  std::vector<std::uint64_t> sizes(const json& j, const std::string& path) const;  // positive, distinct
  // The block's "seeds", or {1} when it has none.
  std::vector<std::uint64_t> seeds(const json& object, const std::string& path) const;
  // A non-empty list of distinct names, each checked by `check` (which throws what registries throw).
  std::vector<std::string> names(const json& j, const std::string& path, std::string_view if_empty,
                                 const std::function<void(const std::string&)>& check) const;
  // The block's "kernels", distinct "float" and "exact"; float alone when it has none.
  std::vector<Kernel> kernels(const json& object, const std::string& path) const;

  // {"k": v, ...} against `specs`, each parameter checked at its own path. A generator's n and
  // seed come from the block's sizes and seeds, not from here.
  ParamAssignments params(const json& j, const std::string& path, const std::vector<ParamSpec>& specs,
                          const std::string& owner, bool generator) const;

  // A heuristic: a label, "NAME" or "NAME:k=v,...", or {"name": NAME, "params": {...}}; returns the
  // label the runs carry. `identity` receives the name and resolved parameters, which tell repeats apart.
  std::string heuristic(const json& j, const std::string& path, std::string& identity) const;
  std::vector<std::string> heuristics(const json& j, const std::string& path) const;

  // Plain generator names of a 3D scene list, or any scene list with `allow_2d` (`what` names the
  // experiment in messages); the ones taking a size are added to `sized`.
  std::vector<std::string> generator_names(const json& j, const std::string& path, const std::string& what,
                                           std::vector<const GeneratorInfo*>& sized, bool allow_2d = false) const;
  // A block's "sizes" for the generators `sized`: required when there is one, within each one's range.
  std::vector<std::uint64_t> generator_sizes(const json& object, const std::string& path,
                                             const std::vector<const GeneratorInfo*>& sized) const;
  // Every size of `sizes` (at `path`) within g's range of n.
  void check_range(const GeneratorInfo& g, const std::vector<std::uint64_t>& sizes, const std::string& path) const;

 private:
  std::string file_;
  std::filesystem::path dir_;
};

// g's `n` parameter; nullptr when it takes no size.
const ParamSpec* n_spec(const GeneratorInfo& g);
// The sizes of `sizes` within g's range of n, or one run at its defaults ({0}) when g takes no size.
std::vector<std::uint64_t> sizes_in_range(const GeneratorInfo& g, const std::vector<std::uint64_t>& sizes);

}  // namespace bsp::experiments
