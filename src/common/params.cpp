#include "common/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/errors.h"

namespace bsp {

std::pair<std::string, std::string> parse_assignment(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw UsageError("parameter '" + std::string(text) + "' is not of the form key=value");
  return {std::string(text.substr(0, eq)), std::string(text.substr(eq + 1))};
}

namespace {

double parse_number(const ParamSpec& spec, const std::string& text, std::string_view owner) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  const bool ok = ec == std::errc() && ptr == end && std::isfinite(value);
  const bool integral = spec.kind != ParamSpec::Kind::Integer || value == std::floor(value);
  if (!ok || !integral)
    throw UsageError(std::string(owner) + ": parameter " + spec.name + "='" + text + "' is not " +
                     (spec.kind == ParamSpec::Kind::Integer ? "an integer" : "a finite number"));
  if (value < spec.min || value > spec.max) {
    std::ostringstream os;
    os << owner << ": parameter " << spec.name << "=" << text << " is outside [" << spec.min << ", "
       << spec.max << "]";
    throw UsageError(os.str());
  }
  return value;
}

}  // namespace

ParamSet ParamSet::resolve(std::span<const ParamSpec> specs, const ParamAssignments& given,
                           std::string_view owner) {
  ParamSet set;
  for (const auto& spec : specs) {
    Value v{spec.kind, spec.default_value, spec.choices.empty() ? "" : spec.choices.front()};
    set.values_[spec.name] = v;
  }
  for (const auto& [key, text] : given) {
    // An init-capture: clang before 16 cannot capture a structured binding (the fuzz build uses clang 14).
    auto spec = std::find_if(specs.begin(), specs.end(), [&name = key](const ParamSpec& s) { return s.name == name; });
    if (spec == specs.end()) {
      std::string known;
      for (const auto& s : specs) known += (known.empty() ? "" : ", ") + s.name;
      throw UsageError(std::string(owner) + ": unknown parameter '" + key + "' (known: " +
                       (known.empty() ? "none" : known) + ")");
    }
    Value& v = set.values_[key];
    if (spec->kind == ParamSpec::Kind::Choice) {
      if (std::find(spec->choices.begin(), spec->choices.end(), text) == spec->choices.end())
        throw UsageError(std::string(owner) + ": parameter " + key + "='" + text + "' is not one of its choices");
      v.text = text;
    } else {
      v.number = parse_number(*spec, text, owner);
    }
  }
  return set;
}

const ParamSet::Value& ParamSet::at(std::string_view name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("parameter not declared: " + std::string(name));
  return it->second;
}

double ParamSet::real(std::string_view name) const { return at(name).number; }
std::int64_t ParamSet::integer(std::string_view name) const {
  return static_cast<std::int64_t>(at(name).number);
}
const std::string& ParamSet::choice(std::string_view name) const { return at(name).text; }
bool ParamSet::has(std::string_view name) const { return values_.count(name) != 0; }

nlohmann::json ParamSet::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : values_) {
    if (v.kind == ParamSpec::Kind::Choice) j[k] = v.text;
    else if (v.kind == ParamSpec::Kind::Integer) j[k] = static_cast<std::int64_t>(v.number);
    else j[k] = v.number;
  }
  return j;
}

std::string ParamSet::canonical() const {
  std::string out;
  for (const auto& [k, v] : values_) {
    if (!out.empty()) out += ',';
    out += k + "=";
    if (v.kind == ParamSpec::Kind::Choice) out += v.text;
    else {
      std::ostringstream os;
      os.precision(17);
      os << v.number;
      out += os.str();
    }
  }
  return out;
}

nlohmann::json specs_to_json(std::span<const ParamSpec> specs) {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : specs) {
    nlohmann::json j{{"name", s.name}, {"doc", s.doc}};
    if (s.kind == ParamSpec::Kind::Choice) {
      j["type"] = "choice";
      j["choices"] = s.choices;
      j["default"] = s.choices.empty() ? "" : s.choices.front();
    } else {
      j["type"] = s.kind == ParamSpec::Kind::Integer ? "integer" : "real";
      if (s.kind == ParamSpec::Kind::Integer) j["default"] = static_cast<std::int64_t>(s.default_value);
      else j["default"] = s.default_value;
      if (s.min > -1e300) j["min"] = s.min;
      if (s.max < 1e300) j["max"] = s.max;
    }
    arr.push_back(j);
  }
  return arr;
}

}  // namespace bsp
