#pragma once
// Suites users write: a JSON file (analysis/SUITE_SCHEMA.md) read into the Suite the built-in ones
// are (suite.h), so it expands, shards, journals and reports the same way. Everything is checked
// before anything runs: scenes, heuristics and their parameters against the registries, sizes
// against each generator's `n` range, mesh files by reading them. Unknown keys, wrong types, empty
// lists and repeated entries are errors; so are animate and Doom blocks, which a suite file cannot
// express (run the dynamic and doom suites, or bspbench animate and bspbench doom).
#include <string>
#include <string_view>

#include "sweep/suite.h"

namespace bsp::sweep {

// Whether `bspbench sweep --suite ARG` names a suite file rather than a built-in suite: ARG ends in
// ".json" or holds a '/' (built-in names have neither).
bool names_suite_file(std::string_view arg);

// Reads the suite file at `path`; file scenes are found relative to its directory. Throws
// InputError with one line, "PATH: JSON.PATH: problem" (for malformed JSON, "PATH: malformed JSON
// at line L, column C: ..."). The suite's source holds `path` and the file's text.
Suite load_suite_file(const std::string& path);

// load_suite_file on text already read: `path` names it in messages and places its file scenes.
Suite parse_suite_file(const std::string& text, const std::string& path);

}  // namespace bsp::sweep
