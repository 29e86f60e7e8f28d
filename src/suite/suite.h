#pragma once
// A suite: named sets of runs, as data. Every suite, built-in or a user's, is a JSON file
// (analysis/SUITE_SCHEMA.md) read by one parser (suite_file.h) into blocks, each block of one
// experiment kind (src/kinds/kinds.h) and parsed by that kind. The built-in suites are the files of
// analysis/suites/ (catalog.h).
#include <memory>
#include <string>
#include <vector>

#include "experiments/kind.h"

namespace bsp::suite {

struct SuiteBlock {
  const experiments::Kind* kind = nullptr;
  std::shared_ptr<const experiments::Block> block;
};

// The file a suite was read from, as named, and its text, whose hash joins the suite's definition
// so an edited file never resumes a journal of the old one.
struct SuiteSource {
  std::string path;
  std::string text;
};

struct Suite {
  std::string name;
  std::string summary;  // one line: what it runs
  std::vector<SuiteBlock> blocks;
  SuiteSource source = {};
};

}  // namespace bsp::suite
