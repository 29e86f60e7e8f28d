#pragma once
// An allocator for a build's large scratch arrays. Arrays of at least kPageAllocationBytes are
// mapped from the system and unmapped when freed (mmap/munmap), so the memory they held goes back
// at once; the C library's heap keeps freed memory to reuse it, and a large array allocated later
// cannot always use what several smaller ones freed, so a build's peak resident memory would
// include scratch it no longer needs. Smaller arrays come from the heap as usual. Fresh mapped
// pages cost no memory until written, so reserving an upper bound is free.
//
// Arrays of at least kHugePageBytes are advised into transparent huge pages (MADV_HUGEPAGE):
// a build writes its fragments into fresh memory, and faulting it in 4 KiB at a time took a
// quarter of a million-polygon build (docs/results/scaling.md). The advice is a hint: where the
// system disables huge pages, or none is free, the kernel maps 4 KiB pages as before. It adds at
// most one partly written 2 MiB page per array to the resident memory.
#include <sys/mman.h>

#include <cstddef>
#include <new>
#include <vector>

namespace bsp {

inline constexpr std::size_t kPageAllocationBytes = std::size_t{1} << 16;
inline constexpr std::size_t kHugePageBytes = std::size_t{1} << 21;

template <class T>
struct PageAllocator {
  using value_type = T;

  PageAllocator() = default;
  template <class U>
  PageAllocator(const PageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kPageAllocationBytes) return static_cast<T*>(::operator new(bytes));
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    if (bytes >= kHugePageBytes) madvise(p, bytes, MADV_HUGEPAGE);
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kPageAllocationBytes) ::operator delete(p);
    else munmap(p, bytes);
  }

  template <class U>
  bool operator==(const PageAllocator<U>&) const noexcept { return true; }
};

template <class T>
using PageVector = std::vector<T, PageAllocator<T>>;

// Frees a vector's memory now; `v = {}` would pick the initializer-list assignment and keep the
// capacity.
template <class Vector>
void free_memory(Vector& v) {
  Vector().swap(v);
}

}  // namespace bsp
