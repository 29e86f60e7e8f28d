// The report reader behind `regress` and `merge-reports` on arbitrary bytes: read_report must
// accept the file or throw InputError; an accepted report must go through compare_reports (against
// itself) and merge_reports (alone, and twice, which is a duplicate shard) with at most an
// InputError or UsageError. Any other exception or a sanitizer report is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "sweep/merge.h"
#include "sweep/regress.h"
#include "sweep/report.h"

namespace {

using namespace bsp;

const std::string& report_path() {
  static const std::string path = [] {
    char pattern[] = "/tmp/bspbench_fuzz_report_XXXXXX";
    return std::string(::mkdtemp(pattern)) + "/report.json";
  }();
  return path;
}

template <class F>
void expect_accepted_or_user_error(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  } catch (const UsageError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::ofstream(report_path(), std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  nlohmann::json report;
  try {
    report = sweep::read_report(report_path());
  } catch (const InputError&) {
    return 0;
  }
  expect_accepted_or_user_error([&] {
    std::ostringstream out;
    sweep::print_regress(sweep::compare_reports(report, report, {}), out);
  });
  expect_accepted_or_user_error([&] { sweep::merge_reports({{"a.json", report}}); });
  expect_accepted_or_user_error([&] { sweep::merge_reports({{"a.json", report}, {"b.json", report}}); });
  return 0;
}
