#include "roofline.h"

#include <immintrin.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include "bench_common.h"
#include "metrics/statistics.h"

namespace bsp::bench {

namespace {

using Clock = std::chrono::steady_clock;

// Independent accumulators: enough to cover an FMA's latency on both of a core's FMA pipes (Zen:
// 4 or 5 cycles, 2 pipes), so the loop runs at the throughput bound, not the latency bound.
constexpr int kChains = 12;
constexpr std::int64_t kFmaLoops = 20'000'000;
// The streamed array: larger than any last-level cache this runs on (32 MiB here), 8 times over.
constexpr std::size_t kStreamBytes = std::size_t{256} << 20;

// Returns FMAs per second; `sink` keeps the result alive.
__attribute__((target("avx2,fma"))) double fma_rate_avx2(double& sink) {
  __m256d acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm256_set1_pd(1.0 + c * 1e-3);
  const __m256d a = _mm256_set1_pd(0.999999), b = _mm256_set1_pd(1e-7);
  const auto start = Clock::now();
  for (std::int64_t i = 0; i < kFmaLoops; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = _mm256_fmadd_pd(acc[c], a, b);
  const double seconds = seconds_since(start);
  __m256d sum = acc[0];
  for (int c = 1; c < kChains; ++c) sum = _mm256_add_pd(sum, acc[c]);
  sink += _mm256_cvtsd_f64(sum);
  return static_cast<double>(kFmaLoops) * kChains * 4 / seconds;
}

double fma_rate_sse2(double& sink) {
  __m128d acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = _mm_set1_pd(1.0 + c * 1e-3);
  const __m128d a = _mm_set1_pd(0.999999), b = _mm_set1_pd(1e-7);
  const auto start = Clock::now();
  for (std::int64_t i = 0; i < kFmaLoops; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = _mm_add_pd(_mm_mul_pd(acc[c], a), b);
  const double seconds = seconds_since(start);
  __m128d sum = acc[0];
  for (int c = 1; c < kChains; ++c) sum = _mm_add_pd(sum, acc[c]);
  sink += _mm_cvtsd_f64(sum);
  return static_cast<double>(kFmaLoops) * kChains * 2 / seconds;
}

// Bytes per second of one pass summing the array with four vector accumulators.
double read_rate(const std::vector<double>& data, double& sink) {
  __m128d acc[4] = {_mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd()};
  const double* p = data.data();
  const auto start = Clock::now();
  for (std::size_t i = 0; i + 8 <= data.size(); i += 8)
    for (int c = 0; c < 4; ++c) acc[c] = _mm_add_pd(acc[c], _mm_load_pd(p + i + 2 * c));
  const double seconds = seconds_since(start);
  sink += _mm_cvtsd_f64(_mm_add_pd(_mm_add_pd(acc[0], acc[1]), _mm_add_pd(acc[2], acc[3])));
  return static_cast<double>(data.size() * sizeof(double)) / seconds;
}

}  // namespace

Roofline measure_roofline(int repeats) {
  Roofline r;
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  std::vector<double> data(kStreamBytes / sizeof(double), 1.0);  // written once: no page faults timed
  double sink = 0;
  std::vector<double> fma, read;
  for (int k = 0; k < repeats; ++k) {
    fma.push_back(avx2 ? fma_rate_avx2(sink) : fma_rate_sse2(sink));
    read.push_back(read_rate(data, sink));
  }
  benchmark::DoNotOptimize(sink);
  r.fma_per_second = median(fma);
  r.read_bytes_per_second = median(read);
  return r;
}

}  // namespace bsp::bench
