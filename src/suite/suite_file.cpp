#include "suite/suite_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "experiments/block_reader.h"
#include "experiments/plugin_loader.h"
#include "kinds/kinds.h"

namespace bsp::suite {

namespace {

using experiments::child;
using experiments::element;
using nlohmann::json;
namespace fs = std::filesystem;

// The name becomes part of the journal's file name.
constexpr std::size_t kMaxNameLength = 64;

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

std::string suite_name(const experiments::BlockReader& r, const json& j) {
  const std::string name = r.string(j, "name");
  const bool ok = !name.empty() && name.size() <= kMaxNameLength && std::isalnum(static_cast<unsigned char>(name[0])) &&
                  std::all_of(name.begin(), name.end(), [](unsigned char c) {
                    return std::isalnum(c) || c == '-' || c == '_' || c == '.';
                  });
  if (!ok)
    r.fail("name", "'" + name + "' is not a suite name (letters, digits, '-', '_' and '.', starting with a letter or "
                   "digit, at most " + std::to_string(kMaxNameLength) + " characters)");
  return name;
}

// The kinds' keys, for messages: "blocks", "merges", ... or "doom".
std::string kind_keys() {
  std::string out;
  const auto all = kinds();
  for (std::size_t i = 0; i < all.size(); ++i) {
    out += i == 0 ? "" : i + 1 == all.size() ? " or " : ", ";
    out.append("\"").append(all[i]->suite_key).append("\"");
  }
  return out;
}

void check_top_keys(const experiments::BlockReader& r, const json& root) {
  std::vector<std::string> known = {"name", "summary", "plugins"};
  for (const auto* k : kinds()) known.emplace_back(k->suite_key);
  for (const auto& item : root.items())
    if (std::find(known.begin(), known.end(), item.key()) == known.end())
      r.fail("", "unknown key '" + item.key() + "' (known: " + experiments::join(known) + ")");
}

// Every block must run something: a block whose sizes all miss its generators' ranges would
// otherwise vanish from the sweep without a word.
void check_runs(const experiments::BlockReader& r, const experiments::Block& block, const std::string& path) {
  if (r.at(path, [&] { return block.expand(); }).empty())
    r.fail(path, "no runs (no size lies in the range of n of any scene)");
}

Suite parse(const experiments::BlockReader& r, const json& root) {
  r.expect(root, root.is_object(), "", "an object");
  check_top_keys(r, root);
  Suite suite;
  suite.name = suite_name(r, r.required(root, "", "name"));
  if (const json* s = r.optional(root, "summary")) suite.summary = r.string(*s, "summary");
  // Plugins first: the blocks may name their heuristics. A path is relative to the suite's folder.
  if (const json* plugins = r.optional(root, "plugins"))
    r.each(*plugins, "plugins", "leave \"plugins\" out", [&](const json& j, const std::string& path) {
      const fs::path file = r.dir() / r.string(j, path);
      r.at(path, [&] { return experiments::load_plugin(file.string()); });
    });
  for (const experiments::Kind* kind : kinds()) {
    const std::string key(kind->suite_key);
    const json* blocks = r.optional(root, key.c_str());
    if (!blocks) continue;
    r.each(*blocks, key, "leave \"" + key + "\" out", [&](const json& j, const std::string& path) {
      std::shared_ptr<const experiments::Block> block = kind->parse(r, j, path);
      if (!block) return;
      // Doom blocks are not expanded here: that reads their IWADs, which expansion does anyway.
      if (kind->expand_when_parsed) check_runs(r, *block, path);
      suite.blocks.push_back({kind, std::move(block)});
    });
  }
  if (suite.blocks.empty()) r.fail("", "no runs: give " + kind_keys());
  return suite;
}

}  // namespace

bool names_suite_file(std::string_view arg) {
  return arg.ends_with(".json") || arg.find('/') != std::string_view::npos;
}

Suite parse_suite_file(const std::string& text, const std::string& path) {
  const json root = parse_json(text, path);
  Suite suite = parse(experiments::BlockReader(path, fs::path(path).parent_path()), root);
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

}  // namespace bsp::suite
