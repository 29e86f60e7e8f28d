#pragma once
// Reading a suite file (analysis/SUITE_SCHEMA.md). Everything is checked before anything runs:
// unknown keys, wrong types, empty lists and repeated entries are errors; each kind's blocks are
// read by the kind (experiments/kind.h), which checks scenes, heuristics and their parameters
// against the registries, sizes against each generator's range, mesh files by reading them; and a
// block that would run nothing is refused.
#include <string>
#include <string_view>

#include "suite/suite.h"

namespace bsp::suite {

// Whether `bspbench sweep --suite ARG` names a suite file rather than a built-in suite: ARG ends in
// ".json" or holds a '/' (built-in names have neither).
bool names_suite_file(std::string_view arg);

// Reads the suite file at `path`; file scenes are found relative to its directory. Throws
// InputError with one line, "PATH: JSON.PATH: problem" (for malformed JSON, "PATH: malformed JSON
// at line L, column C: ..."). The suite's source holds `path` and the file's text.
Suite load_suite_file(const std::string& path);

// load_suite_file on text already read: `path` names it in messages and places its file scenes.
Suite parse_suite_file(const std::string& text, const std::string& path);

}  // namespace bsp::suite
