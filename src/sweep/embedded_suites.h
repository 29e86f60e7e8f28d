#pragma once
// The built-in suite files, compiled in (cmake/embed_suites.cmake generates the definition).
#include <span>
#include <string_view>

namespace bsp::sweep {

struct EmbeddedSuite {
  std::string_view name;  // the file's stem, which is the suite's name
  std::string_view path;  // relative to the repository, e.g. analysis/suites/quick.json
  std::string_view text;
};
// Sorted by path.
std::span<const EmbeddedSuite> embedded_suites();

}  // namespace bsp::sweep
