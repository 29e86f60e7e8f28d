#pragma once
// The ceilings of this machine for plane-side tests (BuildStats::side_tests), on one core, measured
// in the run (Williams, Waterman and Patterson's roofline: a kernel is bound by compute or by memory
// traffic, whichever allows fewer operations per second):
//  - compute: the vector fused multiply-add rate in double precision, from a loop of independent
//    FMAs (AVX2 + FMA when the CPU reports them at run time, else SSE2 multiply-then-add pairs).
//    A side test is n . p - d: three multiply-adds.
//  - memory: the read bandwidth of one core streaming an array 8 times the size of the last-level
//    cache, over the bytes a test reads. A test that reads its own point (a vertex: 24 bytes of
//    double position, as the partition's and the per-vertex paths do) is bound at bandwidth / 24;
//    the scorers' batched tests read one bounding sphere and id (36 bytes) per fragment for k
//    planes, 36 / k bytes per test, so their memory bound is k / 36 of the bandwidth.
// A test is a compare after the multiply-adds, so neither bound counts the branch that follows it.
// The compute bound holds for every test; which bound binds depends on the bytes per test.
#include <cstddef>

namespace bsp::bench {

struct Roofline {
  double fma_per_second = 0;         // double-precision FMAs, all vector lanes counted
  double read_bytes_per_second = 0;  // streaming reads from memory

  static constexpr double kFmaPerTest = 3;
  static constexpr double kVertexBytes = 24;
  double compute_tests_per_second() const { return fma_per_second / kFmaPerTest; }
  // Tests per second when each reads its own vertex from memory.
  double memory_tests_per_second() const { return read_bytes_per_second / kVertexBytes; }
};

// The median of `repeats` timings of each kernel.
Roofline measure_roofline(int repeats);

}  // namespace bsp::bench
