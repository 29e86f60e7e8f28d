#include "sweep/suite_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "animation.h"
#include "catalog.h"
#include "common/errors.h"
#include "dynamic/updater.h"
#include "io/mesh_reader.h"
#include "mesh_scenes.h"
#include "solid_pairs.h"
#include "split/registry.h"
#include "sweep/doom_run.h"
#include "sweep/job.h"
#include "sweep/node_builders.h"

namespace bsp::sweep {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// The bounds the CLI puts on the same settings (bspbench occlude --views, merge --points, the
// generators' seed), so a suite file asks nothing the commands would refuse.
constexpr std::uint64_t kMaxViews = 1000;
constexpr std::uint64_t kMaxPoints = 100'000'000;
constexpr std::uint64_t kMaxSeed = 9'000'000'000'000'000;
constexpr std::uint64_t kDefaultPoints = 10000;
constexpr std::uint32_t kDefaultOccludeViews = 4;
// The name becomes part of the journal's file name.
constexpr std::size_t kMaxNameLength = 64;

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}
std::string element(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// nlohmann keeps the last of two equal keys without a word; a suite file that says a thing twice
// is rejected instead, with the JSON path of the object.
json parse_json(const std::string& text, const std::string& file) {
  struct Frame {
    bool array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  std::vector<Frame> stack;
  const auto where = [&] {
    std::string path;
    for (std::size_t i = 1; i < stack.size(); ++i)
      path = stack[i - 1].array ? element(path, stack[i - 1].index) : child(path, stack[i - 1].key);
    return path;
  };
  const auto value_done = [&] {
    if (!stack.empty() && stack.back().array) ++stack.back().index;
  };
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: stack.push_back({false, 0, {}, {}}); break;
      case json::parse_event_t::array_start: stack.push_back({true, 0, {}, {}}); break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        if (!stack.back().keys.insert(key).second) {
          const std::string path = where();
          throw InputError(file + ": " + (path.empty() ? "" : path + ": ") + "key '" + key + "' given twice");
        }
        stack.back().key = key;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        value_done();
        break;
      case json::parse_event_t::value: value_done(); break;
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..."
    std::string what = e.what();
    const auto at = what.find(" at line ");
    what = at == std::string::npos ? what : what.substr(at + 1);
    throw InputError(file + ": malformed JSON " + what);
  }
}

class SuiteParser {
 public:
  SuiteParser(std::string file, fs::path dir) : file_(std::move(file)), dir_(std::move(dir)) {}

  Suite parse(const json& root) {
    expect(root, root.is_object(), "", "an object");
    check_keys(root, "", {"name", "summary", "blocks", "merges", "occlusions", "animations", "doom"});
    Suite suite;
    suite.name = suite_name(required(root, "", "name"));
    if (const json* s = optional(root, "summary")) suite.summary = string(*s, "summary");
    if (const json* b = optional(root, "blocks"))
      each(*b, "blocks", "leave \"blocks\" out for a suite without drawing runs",
           [&](const json& j, const std::string& path) { suite.blocks.push_back(block(j, path)); });
    if (const json* m = optional(root, "merges"))
      each(*m, "merges", "leave \"merges\" out",
           [&](const json& j, const std::string& path) { suite.merges.push_back(merge_block(j, path)); });
    if (const json* a = optional(root, "animations"))
      each(*a, "animations", "leave \"animations\" out",
           [&](const json& j, const std::string& path) { suite.animations.push_back(animate_block(j, path)); });
    if (const json* o = optional(root, "occlusions"))
      each(*o, "occlusions", "leave \"occlusions\" out",
           [&](const json& j, const std::string& path) { suite.occlusions.push_back(occlude_block(j, path)); });
    if (const json* d = optional(root, "doom"))
      each(*d, "doom", "leave \"doom\" out",
           [&](const json& j, const std::string& path) { suite.doom.push_back(doom_block(j, path)); });
    if (suite.blocks.empty() && suite.merges.empty() && suite.animations.empty() && suite.occlusions.empty() &&
        suite.doom.empty())
      fail("", "no runs: give \"blocks\", \"merges\", \"animations\", \"occlusions\" or \"doom\"");
    check_runs(suite);
    return suite;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(file_ + ": " + (path.empty() ? "" : path + ": ") + what);
  }

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

  void expect(const json& j, bool ok, const std::string& path, const char* noun) const {
    if (ok) return;
    fail(path, std::string("expected ") + noun + ", got " + (j.is_number() ? j.dump() : std::string(j.type_name())));
  }

  void check_keys(const json& object, const std::string& path, std::initializer_list<std::string_view> known) const {
    for (const auto& [key, value] : object.items())
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        std::vector<std::string> names(known.begin(), known.end());
        fail(path, "unknown key '" + key + "' (known: " + join(names) + ")");
      }
  }

  static const json* optional(const json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  const json& required(const json& object, const std::string& path, const char* key) const {
    const json* j = optional(object, key);
    if (!j) fail(path, std::string("missing key '") + key + "'");
    return *j;
  }

  std::string string(const json& j, const std::string& path) const {
    expect(j, j.is_string(), path, "a string");
    return j.get<std::string>();
  }

  bool boolean(const json& j, const std::string& path) const {
    expect(j, j.is_boolean(), path, "true or false");
    return j.get<bool>();
  }

  std::uint64_t integer(const json& j, const std::string& path, std::uint64_t min, std::uint64_t max) const {
    expect(j, j.is_number_integer(), path, "an integer");
    if (j.is_number_unsigned()) {
      const auto v = j.get<std::uint64_t>();
      if (v >= min && v <= max) return v;
      if (v > max) fail(path, j.dump() + " is more than " + std::to_string(max));
    }
    fail(path, j.dump() + " is less than " + std::to_string(min));
  }

  double real(const json& j, const std::string& path, double min, double max, bool open_min = false) const {
    expect(j, j.is_number(), path, "a number");
    const double v = j.get<double>();
    if (open_min ? v <= min : v < min) fail(path, j.dump() + (open_min ? " is not more than " : " is less than ") + json(min).dump());
    if (v > max) fail(path, j.dump() + " is more than " + json(max).dump());
    return v;
  }

  // A non-empty array, each element given to f with its path.
  void each(const json& j, const std::string& path, std::string_view if_empty,
            const std::function<void(const json&, const std::string&)>& f) const {
    expect(j, j.is_array(), path, "an array");
    if (j.empty()) fail(path, "empty list (" + std::string(if_empty) + ")");
    for (std::size_t i = 0; i < j.size(); ++i) f(j[i], element(path, i));
  }

  // Remembers `identity` of the element at `path`; a second element with the same identity is an error.
  void once(std::map<std::string, std::string>& seen, const std::string& identity, const std::string& path) const {
    const auto [it, fresh] = seen.emplace(identity, path);
    if (!fresh) fail(path, "repeats " + it->second);
  }

  std::vector<std::uint64_t> integers(const json& j, const std::string& path, std::uint64_t min, std::uint64_t max,
                                      std::string_view if_empty) const {
    std::vector<std::uint64_t> out;
    std::map<std::string, std::string> seen;
    each(j, path, if_empty, [&](const json& v, const std::string& p) {
      out.push_back(integer(v, p, min, max));
      once(seen, std::to_string(out.back()), p);
    });
    return out;
  }

  std::vector<std::uint64_t> seeds(const json& object, const std::string& path) const {
    const json* j = optional(object, "seeds");
    return j ? integers(*j, child(path, "seeds"), 0, kMaxSeed, "give at least one seed") : std::vector<std::uint64_t>{1};
  }

  std::string suite_name(const json& j) const {
    const std::string name = string(j, "name");
    const bool ok = !name.empty() && name.size() <= kMaxNameLength && std::isalnum(static_cast<unsigned char>(name[0])) &&
                    std::all_of(name.begin(), name.end(), [](unsigned char c) {
                      return std::isalnum(c) || c == '-' || c == '_' || c == '.';
                    });
    if (!ok)
      fail("name", "'" + name + "' is not a suite name (letters, digits, '-', '_' and '.', starting with a letter or "
                    "digit, at most " + std::to_string(kMaxNameLength) + " characters)");
    return name;
  }

  // A parameter's value as the k=v text ParamSet reads, typed by its spec: a number for numbers, a
  // string for choices.
  std::string param_text(const json& v, const ParamSpec& spec, const std::string& path) const {
    if (spec.kind == ParamSpec::Kind::Choice) {
      expect(v, v.is_string(), path, "a string (one of the parameter's choices)");
      return v.get<std::string>();
    }
    expect(v, v.is_number(), path, spec.kind == ParamSpec::Kind::Integer ? "an integer" : "a number");
    return v.is_number_float() ? v.dump() : (v.is_number_unsigned() ? std::to_string(v.get<std::uint64_t>())
                                                                    : std::to_string(v.get<std::int64_t>()));
  }

  // {"k": v, ...} against `specs`, each parameter checked at its own path. n and seed of a
  // generator come from the block's sizes and seeds, not from here.
  ParamAssignments params(const json& j, const std::string& path, const std::vector<ParamSpec>& specs,
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
      const std::string text = param_text(value, *spec, p);
      at(p, [&] { return ParamSet::resolve(specs, {{key, text}}, owner); });
      out.emplace_back(key, text);
    }
    return out;
  }

  // ---- scenes ----

  // A mesh is read once here, so a missing, unreadable or empty one stops the suite before it runs.
  void check_mesh(const std::string& file, const std::string& path) const {
    at(path, [&] { check_scene(read_mesh(file), file); });
  }

  struct ParsedScene {
    SceneSpec spec;
    const GeneratorInfo* generator = nullptr;  // nullptr for meshes
    std::string identity;                      // what makes two scenes of a block the same
  };

  ParsedScene scene(const json& j, const std::string& path) const {
    if (j.is_object()) {
      check_keys(j, path, {"generator", "params"});
      const std::string name = string(required(j, path, "generator"), child(path, "generator"));
      const GeneratorInfo& g = at(child(path, "generator"), [&]() -> const GeneratorInfo& { return find_generator(name); });
      ParamAssignments given;
      if (const json* p = optional(j, "params")) given = params(*p, child(path, "params"), g.params, "scene " + g.name, true);
      const std::string canonical = ParamSet::resolve(g.params, given, g.name).canonical();
      return {SceneSpec(g.name, std::move(given), {}), &g, g.name + " " + canonical};
    }
    const std::string name = string(j, path);
    if (is_file_scene(name)) {
      const std::string written = name.substr(kFileScenePrefix.size());
      if (written.empty()) fail(path, "file: wants a path (relative to the suite file)");
      // Lexically normal, so the runs' commands read the same however the suite file was named.
      const fs::path file = (fs::path(written).is_absolute() ? fs::path(written) : dir_ / written).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) fail(path, "no such file: " + file.string());
      check_mesh(file.string(), path);
      const std::string identity = "file " + fs::weakly_canonical(file, ec).string();
      return {SceneSpec(name, {}, file.string()), nullptr, identity};
    }
    if (is_mesh_scene(name)) {
      const std::string file = at(path, [&] { return mesh_scene_path(name); });
      check_mesh(file, path);
      return {SceneSpec(name, {}, file), nullptr, "mesh " + name};
    }
    const GeneratorInfo& g = at(path, [&]() -> const GeneratorInfo& { return find_generator(name); });
    return {SceneSpec(g.name), &g, g.name + " " + ParamSet::resolve(g.params, {}, g.name).canonical()};
  }

  static const ParamSpec* n_spec(const GeneratorInfo& g) {
    for (const auto& p : g.params)
      if (p.name == "n") return &p;
    return nullptr;
  }

  // Every size of `sizes` (at `path`) within g's range of n.
  void check_range(const GeneratorInfo& g, const std::vector<std::uint64_t>& sizes, const std::string& path) const {
    const ParamSpec* n = n_spec(g);
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      const auto s = static_cast<double>(sizes[i]);
      if (s < n->min || s > n->max) {
        std::ostringstream range;
        range << "[" << n->min << ", " << n->max << "]";
        fail(element(path, i), std::to_string(sizes[i]) + " is outside " + g.name + "'s range of n, " + range.str());
      }
    }
  }

  // ---- heuristics ----

  // A label, "NAME" or "NAME:k=v,...", or {"name": NAME, "params": {...}}; returns the label the
  // runs carry. `identity` receives the name and resolved parameters, which tell repeats apart.
  std::string heuristic(const json& j, const std::string& path, std::string& identity) const {
    if (j.is_object()) {
      check_keys(j, path, {"name", "params"});
      const std::string name = string(required(j, path, "name"), child(path, "name"));
      const HeuristicInfo& h = at(child(path, "name"), [&]() -> const HeuristicInfo& { return find_heuristic(name); });
      ParamAssignments given;
      if (const json* p = optional(j, "params")) given = params(*p, child(path, "params"), h.params, "heuristic " + h.name, false);
      std::string label = h.name;
      for (std::size_t i = 0; i < given.size(); ++i) label += (i == 0 ? ":" : ",") + given[i].first + "=" + given[i].second;
      identity = h.name + " " + ParamSet::resolve(h.params, given, h.name).canonical();
      return label;
    }
    const std::string label = string(j, path);
    const HeuristicVariant v = at(path, [&] { return parse_heuristic_variant(label); });
    const HeuristicInfo& h = at(path, [&]() -> const HeuristicInfo& { return find_heuristic(v.name); });
    if (label.find(':') != std::string::npos && v.params.empty()) fail(path, "no parameters after ':' in '" + label + "'");
    std::set<std::string> keys;
    for (const auto& [k, value] : v.params)
      if (!keys.insert(k).second) fail(path, "parameter '" + k + "' given twice in '" + label + "'");
    identity = h.name + " " + at(path, [&] { return ParamSet::resolve(h.params, v.params, "heuristic " + h.name); }).canonical();
    return label;
  }

  std::vector<std::string> heuristics(const json& j, const std::string& path) const {
    std::vector<std::string> out;
    std::map<std::string, std::string> seen;
    each(j, path, "leave \"heuristics\" out to run every registered heuristic", [&](const json& h, const std::string& p) {
      std::string identity;
      out.push_back(heuristic(h, p, identity));
      once(seen, identity, p);
    });
    return out;
  }

  // ---- blocks ----

  ValidationPlan validation(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"views", "reduce_above", "reduced_views"});
    ValidationPlan plan{1, 0, 1};
    if (const json* v = optional(j, "views")) plan.views = static_cast<std::uint32_t>(integer(*v, child(path, "views"), 0, kMaxViews));
    const json* above = optional(j, "reduce_above");
    const json* reduced = optional(j, "reduced_views");
    if ((above == nullptr) != (reduced == nullptr))
      fail(path, "\"reduce_above\" and \"reduced_views\" come together");
    if (above) {
      plan.reduce_above = integer(*above, child(path, "reduce_above"), 1, std::numeric_limits<std::int64_t>::max());
      plan.reduced_views = static_cast<std::uint32_t>(integer(*reduced, child(path, "reduced_views"), 0, plan.views));
    } else {
      plan.reduced_views = plan.views;
    }
    return plan;
  }

  SuiteBlock block(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"scenes", "heuristics", "incremental", "sizes", "scene_sizes", "seeds", "shapes", "validation"});
    SuiteBlock b;
    if (const json* inc = optional(j, "incremental")) b.incremental = boolean(*inc, child(path, "incremental"));
    // The generators of the block, named or (no "scenes") every drawn one.
    std::vector<const GeneratorInfo*> named;
    if (const json* scenes = optional(j, "scenes")) {
      std::map<std::string, std::string> seen;
      each(*scenes, child(path, "scenes"), "leave \"scenes\" out to run every 3D generator",
           [&](const json& s, const std::string& p) {
             ParsedScene parsed = scene(s, p);
             once(seen, parsed.identity, p);
             if (parsed.generator) named.push_back(parsed.generator);
             b.scenes.push_back(std::move(parsed.spec));
           });
    }
    const bool every_generator = b.scenes.empty();
    std::vector<const GeneratorInfo*> sized;
    if (every_generator) {
      for (const auto& g : generators())
        if (!g.closed_solid && !g.segments && n_spec(g)) sized.push_back(&g);
    } else {
      for (const auto* g : named)
        if (n_spec(*g) && std::find(sized.begin(), sized.end(), g) == sized.end()) sized.push_back(g);
    }
    if (const json* h = optional(j, "heuristics")) {
      if (b.incremental)
        fail(child(path, "heuristics"), "an incremental build consults no heuristic (the insertion order picks the "
                                        "planes); drop \"heuristics\"");
      b.heuristics = heuristics(*h, child(path, "heuristics"));
    }
    sizes(j, path, sized, every_generator, b);
    b.seeds = seeds(j, path);
    b.shapes = {Shape::Strict};
    if (const json* shapes = optional(j, "shapes")) {
      b.shapes.clear();
      std::map<std::string, std::string> seen;
      each(*shapes, child(path, "shapes"), "leave \"shapes\" out for strict trees", [&](const json& s, const std::string& p) {
        const std::string name = string(s, p);
        const auto shape = shape_named(name);
        if (!shape) fail(p, "unknown shape '" + name + "' (known: strict, coarse, leafy)");
        if (b.incremental && *shape == Shape::Leafy) fail(p, "a leafy tree is built recursively, not incrementally");
        once(seen, name, p);
        b.shapes.push_back(*shape);
      });
    }
    if (const json* v = optional(j, "validation")) b.validation = validation(*v, child(path, "validation"));
    else b.validation = {1, 0, 1};
    return b;
  }

  // "sizes" for the sized generators not in "scene_sizes"; "scene_sizes" per generator. A named
  // generator's sizes must lie in its range of n; with every generator (no "scenes"), each runs
  // the sizes in its range, as the built-in suites do.
  void sizes(const json& j, const std::string& path, const std::vector<const GeneratorInfo*>& sized,
             bool every_generator, SuiteBlock& b) const {
    std::set<const GeneratorInfo*> own;
    if (const json* ss = optional(j, "scene_sizes")) {
      const std::string sp = child(path, "scene_sizes");
      expect(*ss, ss->is_object(), sp, "an object");
      if (ss->empty()) fail(sp, "empty object (leave \"scene_sizes\" out)");
      for (const auto& item : ss->items()) {
        const std::string& name = item.key();
        const json& list = item.value();
        const std::string p = child(sp, name);
        const GeneratorInfo& g = at(p, [&]() -> const GeneratorInfo& { return find_generator(name); });
        if (std::find(sized.begin(), sized.end(), &g) == sized.end())
          fail(p, !n_spec(g) ? name + " takes no size" : name + " is not a scene of this block");
        const auto values = integers(list, p, 1, std::numeric_limits<std::int64_t>::max(), "give at least one size");
        check_range(g, values, p);
        b.scene_sizes.push_back({g.name, values});
        own.insert(&g);
      }
    }
    const bool needed = std::any_of(sized.begin(), sized.end(), [&](const GeneratorInfo* g) { return !own.count(g); });
    const json* s = optional(j, "sizes");
    if (!s) {
      if (needed) {
        const auto g = std::find_if(sized.begin(), sized.end(), [&](const GeneratorInfo* x) { return !own.count(x); });
        fail(path, "missing key 'sizes' (" + (every_generator ? std::string("every 3D generator runs, and") : (*g)->name) +
                       " takes a size n)");
      }
      return;
    }
    const std::string p = child(path, "sizes");
    if (!needed)
      fail(p, sized.empty() ? "no scene of this block takes a size (meshes and generators without n run once)"
                            : "every scene of this block that takes a size has its own in \"scene_sizes\"");
    b.sizes = integers(*s, p, 1, std::numeric_limits<std::int64_t>::max(), "give at least one size");
    if (!every_generator)
      for (const auto* g : sized)
        if (!own.count(g)) check_range(*g, b.sizes, p);
  }

  MergeBlock merge_block(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"pairs", "heuristics", "ops", "sizes", "seeds", "points"});
    MergeBlock b;
    std::vector<const SolidPairInfo*> chosen;
    if (const json* pairs = optional(j, "pairs")) {
      std::map<std::string, std::string> seen;
      each(*pairs, child(path, "pairs"), "leave \"pairs\" out to run every solid pair", [&](const json& v, const std::string& p) {
        const std::string name = string(v, p);
        const SolidPairInfo& pair = at(p, [&]() -> const SolidPairInfo& { return find_solid_pair(name); });
        once(seen, pair.name, p);
        b.pairs.push_back(pair.name);
        chosen.push_back(&pair);
      });
    } else {
      for (const auto& pair : solid_pairs()) chosen.push_back(&pair);
    }
    if (const json* h = optional(j, "heuristics")) b.heuristics = heuristics(*h, child(path, "heuristics"));
    if (const json* ops = optional(j, "ops")) {
      std::map<std::string, std::string> seen;
      each(*ops, child(path, "ops"), "leave \"ops\" out for all four", [&](const json& v, const std::string& p) {
        const std::string name = string(v, p);
        const SetOp op = at(p, [&] { return parse_set_op(name); });
        once(seen, name, p);
        b.ops.push_back(op);
      });
    }
    const bool any_sized = std::any_of(chosen.begin(), chosen.end(), [](const SolidPairInfo* p) { return p->sized; });
    if (const json* s = optional(j, "sizes")) {
      const std::string p = child(path, "sizes");
      if (!any_sized) fail(p, "no pair of this block takes a size");
      b.sizes = integers(*s, p, 1, std::numeric_limits<std::int64_t>::max(), "give at least one size");
      if (optional(j, "pairs"))
        for (const auto* pair : chosen)
          for (std::size_t i = 0; pair->sized && i < b.sizes.size(); ++i) {
            const auto n = static_cast<double>(b.sizes[i]);
            if (n < pair->min_n || n > pair->max_n) {
              std::ostringstream range;
              range << "[" << pair->min_n << ", " << pair->max_n << "]";
              fail(element(p, i), std::to_string(b.sizes[i]) + " is outside " + pair->name +
                                      "'s range of polygons per operand, " + range.str());
            }
          }
    } else if (any_sized) {
      fail(path, "missing key 'sizes' (polygons per operand)");
    }
    b.seeds = seeds(j, path);
    b.points = kDefaultPoints;
    if (const json* points = optional(j, "points")) b.points = integer(*points, child(path, "points"), 0, kMaxPoints);
    return b;
  }

  OccludeBlock occlude_block(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"scenes", "sizes", "heuristics", "seeds", "views"});
    OccludeBlock b;
    std::vector<const GeneratorInfo*> sized;
    b.scenes = generator_names(required(j, path, "scenes"), child(path, "scenes"), "occlusion culling", sized);
    b.sizes = generator_sizes(j, path, sized);
    if (const json* h = optional(j, "heuristics")) b.heuristics = heuristics(*h, child(path, "heuristics"));
    b.seeds = seeds(j, path);
    b.views = kDefaultOccludeViews;
    if (const json* v = optional(j, "views")) b.views = static_cast<std::uint32_t>(integer(*v, child(path, "views"), 1, kMaxViews));
    return b;
  }

  // The 3D generators of a block that names them plainly (`what` says which block, for messages).
  std::vector<std::string> generator_names(const json& j, const std::string& path, const std::string& what,
                                           std::vector<const GeneratorInfo*>& sized) const {
    std::vector<std::string> names;
    std::map<std::string, std::string> seen;
    each(j, path, "name at least one generator", [&](const json& v, const std::string& p) {
      const std::string name = v.is_string() ? v.get<std::string>() : std::string();
      if (!v.is_string() || is_mesh_scene(name) || is_file_scene(name))
        fail(p, what + " scenes are generator names (no parameters, files or meshes)");
      const GeneratorInfo& g = at(p, [&]() -> const GeneratorInfo& { return find_generator(name); });
      if (g.segments) fail(p, name + " is 2D; " + what + " wants a 3D scene");
      once(seen, g.name, p);
      names.push_back(g.name);
      if (n_spec(g)) sized.push_back(&g);
    });
    return names;
  }

  // "sizes" of a block of plain generators: required when one takes a size, within each one's range.
  std::vector<std::uint64_t> generator_sizes(const json& j, const std::string& path,
                                             const std::vector<const GeneratorInfo*>& sized) const {
    const json* s = optional(j, "sizes");
    if (!s) {
      if (!sized.empty()) fail(path, "missing key 'sizes' (" + sized.front()->name + " takes a size n)");
      return {};
    }
    const std::string p = child(path, "sizes");
    if (sized.empty()) fail(p, "no scene of this block takes a size");
    auto sizes = integers(*s, p, 1, std::numeric_limits<std::int64_t>::max(), "give at least one size");
    for (const auto* g : sized) check_range(*g, sizes, p);
    return sizes;
  }

  // A non-empty list of distinct names, each checked by `check` (which throws what the registries throw).
  std::vector<std::string> names(const json& j, const std::string& path, std::string_view if_empty,
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

  // The same bounds as `bspbench animate` (generators/animation.h checks them again when a job runs).
  AnimateBlock animate_block(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"scenes", "sizes", "heuristics", "strategies", "moving", "speeds", "seeds", "frames", "object",
                         "object_n", "size", "spin", "check_every", "drift_every", "views"});
    AnimateBlock b;
    std::vector<const GeneratorInfo*> sized;
    b.scenes = generator_names(required(j, path, "scenes"), child(path, "scenes"), "animation", sized);
    b.sizes = generator_sizes(j, path, sized);
    if (const json* h = optional(j, "heuristics")) b.heuristics = heuristics(*h, child(path, "heuristics"));
    if (const json* s = optional(j, "strategies"))
      b.strategies = names(*s, child(path, "strategies"), "leave \"strategies\" out for every strategy",
                           [](const std::string& name) {
                             const auto known = updater_names();
                             if (std::find(known.begin(), known.end(), name) == known.end())
                               throw UsageError("unknown update strategy '" + name + "' (known: " + join(known) + ")");
                           });
    std::map<std::string, std::string> seen;
    each(required(j, path, "moving"), child(path, "moving"), "give at least one count", [&](const json& v, const std::string& p) {
      b.moving.push_back(static_cast<std::uint32_t>(integer(v, p, 0, 1000)));
      once(seen, std::to_string(b.moving.back()), p);
    });
    seen.clear();
    each(required(j, path, "speeds"), child(path, "speeds"), "give at least one speed", [&](const json& v, const std::string& p) {
      b.speeds.push_back(real(v, p, 0, 1));
      once(seen, json(b.speeds.back()).dump(), p);
    });
    b.seeds = seeds(j, path);
    if (const json* v = optional(j, "frames")) b.frames = static_cast<std::uint32_t>(integer(*v, child(path, "frames"), 1, 100000));
    if (const json* v = optional(j, "object")) {
      b.object = string(*v, child(path, "object"));
      if (b.object != kSceneGroups && !at(child(path, "object"), [&] { return find_generator(b.object).closed_solid; }))
        fail(child(path, "object"), "'" + b.object + "' is not a closed solid (bspbench scenes) or '" +
                                        std::string(kSceneGroups) + "'");
    }
    if (const json* v = optional(j, "object_n")) b.object_n = integer(*v, child(path, "object_n"), 1, 100000);
    if (const json* v = optional(j, "size")) b.size = real(*v, child(path, "size"), 0, 0.5, true);
    if (const json* v = optional(j, "spin")) b.spin = real(*v, child(path, "spin"), 0, std::numbers::pi);
    if (const json* v = optional(j, "check_every")) b.check_every = static_cast<std::uint32_t>(integer(*v, child(path, "check_every"), 1, 100000));
    if (const json* v = optional(j, "drift_every")) b.drift_every = static_cast<std::uint32_t>(integer(*v, child(path, "drift_every"), 0, 100000));
    if (const json* v = optional(j, "views")) b.views = static_cast<std::uint32_t>(integer(*v, child(path, "views"), 0, kMaxViews));
    return b;
  }

  // A Doom block's heuristic: a Doom preset's name or a heuristic label.
  std::vector<std::string> doom_heuristics(const json& j, const std::string& path) const {
    std::vector<std::string> out;
    std::map<std::string, std::string> seen;
    each(j, path, "leave \"heuristics\" out for every heuristic and Doom preset", [&](const json& h, const std::string& p) {
      std::string identity;
      if (h.is_string() && doom_preset(h.get<std::string>())) {
        out.push_back(h.get<std::string>());
        identity = "preset " + out.back();
      } else {
        out.push_back(heuristic(h, p, identity));
      }
      once(seen, identity, p);
    });
    return out;
  }

  // IWADs are file names in the Doom data directory; they are read when the suite expands, which
  // names a missing one and the package that has it.
  DoomBlock doom_block(const json& j, const std::string& path) const {
    expect(j, j.is_object(), path, "an object");
    check_keys(j, path, {"iwads", "maps", "heuristics", "builders", "seeds", "views"});
    DoomBlock b;
    b.iwads = names(required(j, path, "iwads"), child(path, "iwads"), "name at least one IWAD", [](const std::string& name) {
      if (name.empty() || name.find('/') != std::string::npos)
        throw UsageError("'" + name + "' is not a file name in the Doom data directory");
    });
    if (const json* m = optional(j, "maps"))
      b.maps = names(*m, child(path, "maps"), "leave \"maps\" out for every map", [](const std::string&) {});
    if (const json* h = optional(j, "heuristics")) b.heuristics = doom_heuristics(*h, child(path, "heuristics"));
    if (const json* bs = optional(j, "builders"))
      b.builders = names(*bs, child(path, "builders"), "leave \"builders\" out for none", check_builder_name);
    b.seeds = seeds(j, path);
    if (const json* v = optional(j, "views")) b.views = static_cast<std::uint32_t>(integer(*v, child(path, "views"), 0, kMaxViews));
    return b;
  }

  // Every block must run something: a block whose sizes all miss its generators' ranges would
  // otherwise vanish from the sweep without a word.
  void check_runs(const Suite& suite) const {
    const auto check = [&](const std::string& path, const Suite& one) {
      const auto jobs = at(path, [&] { return expand(one); });
      if (jobs.empty()) fail(path, "no runs (no size lies in the range of n of any scene)");
    };
    for (std::size_t i = 0; i < suite.blocks.size(); ++i) check(element("blocks", i), Suite{.blocks = {suite.blocks[i]}});
    for (std::size_t i = 0; i < suite.merges.size(); ++i) check(element("merges", i), Suite{.merges = {suite.merges[i]}});
    for (std::size_t i = 0; i < suite.animations.size(); ++i)
      check(element("animations", i), Suite{.animations = {suite.animations[i]}});
    for (std::size_t i = 0; i < suite.occlusions.size(); ++i)
      check(element("occlusions", i), Suite{.occlusions = {suite.occlusions[i]}});
    // Doom blocks are not expanded here: that reads their IWADs, which expansion does anyway.
  }

  std::string file_;
  fs::path dir_;
};

}  // namespace

bool names_suite_file(std::string_view arg) {
  return arg.ends_with(".json") || arg.find('/') != std::string_view::npos;
}

Suite parse_suite_file(const std::string& text, const std::string& path) {
  const json root = parse_json(text, path);
  Suite suite = SuiteParser(path, fs::path(path).parent_path()).parse(root);
  suite.source = {path, text};
  return suite;
}

Suite load_suite_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": no such suite file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the suite file");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return parse_suite_file(text, path);
}

}  // namespace bsp::sweep
