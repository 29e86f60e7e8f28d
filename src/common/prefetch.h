#pragma once
// Prefetching the scattered reads of a loop whose next indices are known: the build's loops over a
// node's fragment ids read each fragment's bounding sphere, plane index or vertices from wherever
// the store put them, one cache miss after another unless asked for ahead.
#include <cstddef>

namespace bsp {

// How many items ahead such a loop asks for what it will read.
inline constexpr std::size_t kPrefetchAhead = 8;

// Asks for every cache line of the `bytes` bytes at `p` (none when bytes is 0).
inline void prefetch_bytes(const void* p, std::size_t bytes) {
  if (bytes == 0) return;
  const char* c = static_cast<const char*>(p);
  for (std::size_t off = 0; off < bytes; off += 64) __builtin_prefetch(c + off);
  __builtin_prefetch(c + bytes - 1);
}

}  // namespace bsp
