#pragma once
// Named, documented, defaulted parameters for heuristics and scene generators. Users set them as
// key=value strings at the edges (CLI, bench, sweeps); resolve() rejects unknown keys and bad values,
// so a typo never silently runs the default.
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace bsp {

struct ParamSpec {
  enum class Kind { Integer, Real, Choice };
  std::string name;
  Kind kind = Kind::Real;
  std::string doc;
  double default_value = 0.0;  // Integer and Real
  double min = -1e300;         // inclusive bounds, Integer and Real
  double max = 1e300;
  std::vector<std::string> choices;  // Choice; the first is the default
};

using ParamAssignments = std::vector<std::pair<std::string, std::string>>;

// Splits "key=value"; throws UsageError when there is no '=' or the key is empty.
std::pair<std::string, std::string> parse_assignment(std::string_view text);

class ParamSet {
 public:
  ParamSet() = default;
  // owner names the heuristic or scene in error messages.
  static ParamSet resolve(std::span<const ParamSpec> specs, const ParamAssignments& given,
                          std::string_view owner);

  double real(std::string_view name) const;
  std::int64_t integer(std::string_view name) const;
  const std::string& choice(std::string_view name) const;
  bool has(std::string_view name) const;

  nlohmann::json to_json() const;
  // Canonical "k=v,k=v" text in key order, used in job keys and hashes.
  std::string canonical() const;

 private:
  struct Value {
    ParamSpec::Kind kind;
    double number = 0.0;
    std::string text;
  };
  const Value& at(std::string_view name) const;
  std::map<std::string, Value, std::less<>> values_;
};

nlohmann::json specs_to_json(std::span<const ParamSpec> specs);

}  // namespace bsp
