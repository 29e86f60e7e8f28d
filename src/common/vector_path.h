#pragma once
// Which vector instructions the batched side tests (FragmentStore::count_sides,
// ExactFragments::count_sides) run on. The build targets the x86-64 baseline, with no -march and
// no fused multiply-adds (CMakeLists.txt), so one binary runs everywhere; the wider path is chosen
// at run time, where the processor has it. Every path does the same operations in the same order,
// lane for lane, so all give the same bits: the choice changes speed, never a decision. Tests run
// each path against the one-pair-at-a-time classification.
#include <cstdint>

namespace bsp {

enum class VectorPath : std::uint8_t {
  Widest,    // AVX (four doubles an instruction) where the processor has it, else Baseline
  Baseline,  // SSE2 (two doubles) on x86-64, scalar elsewhere
};

// True when `path` runs the AVX code on this processor.
inline bool runs_avx(VectorPath path) {
#if defined(__x86_64__) && defined(__GNUC__)
  return path == VectorPath::Widest && __builtin_cpu_supports("avx");
#else
  (void)path;
  return false;
#endif
}

}  // namespace bsp
