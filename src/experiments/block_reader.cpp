#include "experiments/block_reader.h"

#include <algorithm>
#include <limits>
#include <set>
#include <sstream>

#include "catalog.h"
#include "experiments/heuristic_choice.h"
#include "mesh_scenes.h"
#include "tree/exact_build.h"

namespace bsp::experiments {

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string element(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

const ParamSpec* n_spec(const GeneratorInfo& g) {
  for (const auto& p : g.params)
    if (p.name == "n") return &p;
  return nullptr;
}

std::vector<std::uint64_t> sizes_in_range(const GeneratorInfo& g, const std::vector<std::uint64_t>& sizes) {
  const ParamSpec* n = n_spec(g);
  if (!n) return {0};
  std::vector<std::uint64_t> out;
  for (auto s : sizes)
    if (static_cast<double>(s) >= n->min && static_cast<double>(s) <= n->max) out.push_back(s);
  return out;
}

void BlockReader::fail(const std::string& path, const std::string& what) const {
  throw InputError(file_ + ": " + (path.empty() ? "" : path + ": ") + what);
}

void BlockReader::expect(const json& j, bool ok, const std::string& path, const char* noun) const {
  if (ok) return;
  fail(path, std::string("expected ") + noun + ", got " + (j.is_number() ? j.dump() : std::string(j.type_name())));
}

void BlockReader::check_keys(const json& object, const std::string& path,
                             std::initializer_list<std::string_view> known) const {
  for (const auto& [key, value] : object.items())
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::vector<std::string> names(known.begin(), known.end());
      fail(path, "unknown key '" + key + "' (known: " + join(names) + ")");
    }
}

const nlohmann::json* BlockReader::optional(const json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const nlohmann::json& BlockReader::required(const json& object, const std::string& path, const char* key) const {
  const json* j = optional(object, key);
  if (!j) fail(path, std::string("missing key '") + key + "'");
  return *j;
}

std::string BlockReader::string(const json& j, const std::string& path) const {
  expect(j, j.is_string(), path, "a string");
  return j.get<std::string>();
}

bool BlockReader::boolean(const json& j, const std::string& path) const {
  expect(j, j.is_boolean(), path, "true or false");
  return j.get<bool>();
}

std::uint64_t BlockReader::integer(const json& j, const std::string& path, std::uint64_t min, std::uint64_t max) const {
  expect(j, j.is_number_integer(), path, "an integer");
  if (j.is_number_unsigned()) {
    const auto v = j.get<std::uint64_t>();
    if (v >= min && v <= max) return v;
    if (v > max) fail(path, j.dump() + " is more than " + std::to_string(max));
  }
  fail(path, j.dump() + " is less than " + std::to_string(min));
}

double BlockReader::real(const json& j, const std::string& path, double min, double max, bool open_min) const {
  expect(j, j.is_number(), path, "a number");
  const double v = j.get<double>();
  if (open_min ? v <= min : v < min)
    fail(path, j.dump() + (open_min ? " is not more than " : " is less than ") + json(min).dump());
  if (v > max) fail(path, j.dump() + " is more than " + json(max).dump());
  return v;
}

void BlockReader::each(const json& j, const std::string& path, std::string_view if_empty,
                       const std::function<void(const json&, const std::string&)>& f) const {
  expect(j, j.is_array(), path, "an array");
  if (j.empty()) fail(path, "empty list (" + std::string(if_empty) + ")");
  for (std::size_t i = 0; i < j.size(); ++i) f(j[i], element(path, i));
}

void BlockReader::once(std::map<std::string, std::string>& seen, const std::string& identity,
                       const std::string& path) const {
  const auto [it, fresh] = seen.emplace(identity, path);
  if (!fresh) fail(path, "repeats " + it->second);
}

std::vector<std::uint64_t> BlockReader::integers(const json& j, const std::string& path, std::uint64_t min,
                                                 std::uint64_t max, std::string_view if_empty) const {
  std::vector<std::uint64_t> out;
  std::map<std::string, std::string> seen;
  each(j, path, if_empty, [&](const json& v, const std::string& p) {
    out.push_back(integer(v, p, min, max));
    once(seen, std::to_string(out.back()), p);
  });
  return out;
}

std::vector<std::uint64_t> BlockReader::sizes(const json& j, const std::string& path) const {
  return integers(j, path, 1, std::numeric_limits<std::int64_t>::max(), "give at least one size");
}

std::vector<std::uint64_t> BlockReader::seeds(const json& object, const std::string& path) const {
  const json* j = optional(object, "seeds");
  return j ? integers(*j, child(path, "seeds"), 0, kMaxSeed, "give at least one seed") : std::vector<std::uint64_t>{1};
}

std::vector<std::string> BlockReader::names(const json& j, const std::string& path, std::string_view if_empty,
                                            const std::function<void(const std::string&)>& check) const {
  std::vector<std::string> out;
  std::map<std::string, std::string> seen;
  each(j, path, if_empty, [&](const json& v, const std::string& p) {
    const std::string name = string(v, p);
    at(p, [&] { check(name); });
    once(seen, name, p);
    out.push_back(name);
  });
  return out;
}

std::vector<Kernel> BlockReader::kernels(const json& object, const std::string& path) const {
  const json* j = optional(object, "kernels");
  if (!j) return {Kernel::Float};
  std::vector<Kernel> out;
  for (const auto& name : names(*j, child(path, "kernels"), "leave \"kernels\" out for float only", [](const std::string& k) {
         if (!kernel_named(k)) throw UsageError("unknown kernel '" + k + "' (float or exact)");
       }))
    out.push_back(*kernel_named(name));
  return out;
}

namespace {

// A parameter's value as the k=v text ParamSet reads, typed by its spec: a number for numbers, a
// string for choices.
std::string param_text(const BlockReader& r, const nlohmann::json& v, const ParamSpec& spec, const std::string& path) {
  if (spec.kind == ParamSpec::Kind::Choice) {
    r.expect(v, v.is_string(), path, "a string (one of the parameter's choices)");
    return v.get<std::string>();
  }
  r.expect(v, v.is_number(), path, spec.kind == ParamSpec::Kind::Integer ? "an integer" : "a number");
  return v.is_number_float() ? v.dump()
                             : (v.is_number_unsigned() ? std::to_string(v.get<std::uint64_t>())
                                                       : std::to_string(v.get<std::int64_t>()));
}

}  // namespace

ParamAssignments BlockReader::params(const json& j, const std::string& path, const std::vector<ParamSpec>& specs,
                                     const std::string& owner, bool generator) const {
  expect(j, j.is_object(), path, "an object");
  ParamAssignments out;
  // Named, not structured bindings: clang before 16 cannot capture those (the fuzz build uses clang 14).
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    const json& value = item.value();
    const std::string p = child(path, key);
    if (generator && key == "n") fail(p, "a scene's size comes from \"sizes\" (or \"scene_sizes\")");
    if (generator && key == "seed") fail(p, "a scene's seed comes from \"seeds\"");
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == key; });
    if (spec == specs.end()) {
      std::vector<std::string> known;
      for (const auto& s : specs)
        if (!generator || (s.name != "n" && s.name != "seed")) known.push_back(s.name);
      fail(p, owner + ": unknown parameter '" + key + "' (known: " + (known.empty() ? "none" : join(known)) + ")");
    }
    const std::string text = param_text(*this, value, *spec, p);
    at(p, [&] { return ParamSet::resolve(specs, {{key, text}}, owner); });
    out.emplace_back(key, text);
  }
  return out;
}

std::string BlockReader::heuristic(const json& j, const std::string& path, std::string& identity) const {
  if (j.is_object()) {
    check_keys(j, path, {"name", "params"});
    const std::string name = string(required(j, path, "name"), child(path, "name"));
    const std::vector<ParamSpec>& specs = at(child(path, "name"), [&]() -> const std::vector<ParamSpec>& { return params_of(name); });
    ParamAssignments given;
    if (const json* p = optional(j, "params")) given = params(*p, child(path, "params"), specs, "heuristic " + name, false);
    const HeuristicChoice choice = at(path, [&] { return HeuristicChoice::of(name, given); });
    identity = name + " " + choice.resolved.canonical();
    return choice.label;
  }
  const std::string label = string(j, path);
  const HeuristicLabel v = at(path, [&] { return split_heuristic_label(label); });
  at(path, [&] { return params_of(v.name); });
  if (label.find(':') != std::string::npos && v.params.empty()) fail(path, "no parameters after ':' in '" + label + "'");
  std::set<std::string> keys;
  for (const auto& [k, value] : v.params)
    if (!keys.insert(k).second) fail(path, "parameter '" + k + "' given twice in '" + label + "'");
  identity = v.name + " " + at(path, [&] { return HeuristicChoice::of(v.name, v.params); }).resolved.canonical();
  return label;
}

std::vector<std::string> BlockReader::heuristics(const json& j, const std::string& path) const {
  std::vector<std::string> out;
  std::map<std::string, std::string> seen;
  each(j, path, "leave \"heuristics\" out to run every registered heuristic", [&](const json& h, const std::string& p) {
    std::string identity;
    out.push_back(heuristic(h, p, identity));
    once(seen, identity, p);
  });
  return out;
}

std::vector<std::string> BlockReader::generator_names(const json& j, const std::string& path, const std::string& what,
                                                      std::vector<const GeneratorInfo*>& sized, bool allow_2d) const {
  std::vector<std::string> out;
  std::map<std::string, std::string> seen;
  each(j, path, "name at least one generator", [&](const json& v, const std::string& p) {
    const std::string name = v.is_string() ? v.get<std::string>() : std::string();
    if (!v.is_string() || is_mesh_scene(name) || name.starts_with("file:"))
      fail(p, what + " scenes are generator names (no parameters, files or meshes)");
    const GeneratorInfo& g = at(p, [&]() -> const GeneratorInfo& { return find_generator(name); });
    if (g.segments && !allow_2d) fail(p, name + " is 2D; " + what + " wants a 3D scene");
    once(seen, g.name, p);
    out.push_back(g.name);
    if (n_spec(g)) sized.push_back(&g);
  });
  return out;
}

std::vector<std::uint64_t> BlockReader::generator_sizes(const json& object, const std::string& path,
                                                        const std::vector<const GeneratorInfo*>& sized) const {
  const json* s = optional(object, "sizes");
  if (!s) {
    if (!sized.empty()) fail(path, "missing key 'sizes' (" + sized.front()->name + " takes a size n)");
    return {};
  }
  const std::string p = child(path, "sizes");
  if (sized.empty()) fail(p, "no scene of this block takes a size");
  auto out = sizes(*s, p);
  for (const auto* g : sized) check_range(*g, out, p);
  return out;
}

void BlockReader::check_range(const GeneratorInfo& g, const std::vector<std::uint64_t>& values,
                              const std::string& path) const {
  const ParamSpec* n = n_spec(g);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto s = static_cast<double>(values[i]);
    if (s < n->min || s > n->max) {
      std::ostringstream range;
      range << "[" << n->min << ", " << n->max << "]";
      fail(element(path, i), std::to_string(values[i]) + " is outside " + g.name + "'s range of n, " + range.str());
    }
  }
}

}  // namespace bsp::experiments
