#include "sweep/calibration.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "common/rng.h"

namespace bsp::sweep {

namespace {

// Sorting exercises branches and memory like a tree build; the square-root chain exercises the
// floating-point pipeline like plane tests. Sizes fixed forever: changing them invalidates every
// stored calibration.
constexpr std::size_t kSortKeys = std::size_t{1} << 19;
constexpr std::size_t kSqrtSteps = std::size_t{1} << 21;
constexpr int kRepetitions = 3;

std::uint64_t kernel() {
  std::vector<std::uint64_t> keys(kSortKeys);
  for (std::size_t i = 0; i < kSortKeys; ++i) keys[i] = splitmix64(i);
  std::sort(keys.begin(), keys.end());
  double x = 1.0;
  for (std::size_t i = 0; i < kSqrtSteps; ++i) x = std::sqrt(x + static_cast<double>(i & 1023));
  return keys[kSortKeys / 2] ^ static_cast<std::uint64_t>(x * 1e6);
}

}  // namespace

Calibration calibrate() {
  Calibration c;
  c.seconds = 1e300;
  for (int r = 0; r < kRepetitions; ++r) {
    const double start = thread_cpu_seconds();
    c.checksum = kernel();
    c.seconds = std::min(c.seconds, thread_cpu_seconds() - start);
  }
  return c;
}

nlohmann::json to_json(const Calibration& c) {
  return {{"kernel", calibration_kernel_description()}, {"seconds", c.seconds}, {"checksum", c.checksum}};
}

std::string calibration_kernel_description() {
  return "sort 2^19 splitmix64 keys, then a chain of 2^21 square roots; thread CPU time, best of 3";
}

}  // namespace bsp::sweep
