#include "suite/catalog.h"

#include <algorithm>

#include "common/errors.h"
#include "suite/suite_file.h"

namespace bsp::suite {

namespace {

const EmbeddedSuite* builtin(std::string_view name) {
  const auto all = embedded_suites();
  const auto it = std::find_if(all.begin(), all.end(), [&](const EmbeddedSuite& s) { return s.name == name; });
  return it == all.end() ? nullptr : &*it;
}

std::string known_names() {
  std::string known;
  for (const auto& name : builtin_suite_names()) known += (known.empty() ? "" : ", ") + name;
  return known;
}

}  // namespace

std::vector<std::string> builtin_suite_names() {
  std::vector<std::string> names;
  for (const auto& s : embedded_suites()) names.emplace_back(s.name);
  return names;
}

Suite find_suite(std::string_view arg) {
  if (names_suite_file(arg)) {
    Suite suite = load_suite_file(std::string(arg));
    if (const EmbeddedSuite* same = builtin(suite.name); same && same->text != suite.source.text)
      throw InputError(std::string(arg) + ": name: '" + suite.name + "' is a built-in suite; give yours another name");
    return suite;
  }
  const EmbeddedSuite* s = builtin(arg);
  if (!s)
    throw UsageError("unknown suite '" + std::string(arg) + "' (known: " + known_names() + "; or a suite file, FILE.json)");
  return parse_suite_file(std::string(s->text), std::string(s->path));
}

}  // namespace bsp::suite
