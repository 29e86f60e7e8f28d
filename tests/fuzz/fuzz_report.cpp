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
#include "results/shards.h"
#include "gate/regress.h"
#include "results/report.h"

namespace {

using namespace bsp;

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
  // In memory (/dev/shm): writing every input to a disk-backed /tmp made file I/O most of the time.
  const std::string path = "/dev/shm/bspbench_fuzz_report_" + std::to_string(::getpid()) + ".json";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  nlohmann::json report;
  try {
    report = results::read_report(path);
  } catch (const InputError&) {
  }
  std::remove(path.c_str());
  if (report.is_null()) return 0;
  expect_accepted_or_user_error([&] {
    std::ostringstream out;
    gate::print_regress(gate::compare_reports(report, report, {}), out);
  });
  expect_accepted_or_user_error([&] { results::combine_shards({{"a.json", report}}); });
  expect_accepted_or_user_error([&] { results::combine_shards({{"a.json", report}, {"b.json", report}}); });
  return 0;
}
