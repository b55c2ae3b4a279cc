// Memory for the solver's large arrays in whole 2 MiB blocks, advised as transparent huge
// pages (madvise MADV_HUGEPAGE; the kernel may ignore the advice). Where transparent huge
// pages are granted only on advice (the "madvise" setting, common on servers and virtual
// machines), every first touch of a fresh 4 KiB page is a page fault: a cornell solve at
// degree 2 took 185,000 of them, most in the link array's growth (about 2 million links of
// 88 bytes, reallocated as it doubles), 7-12% of its CPU time. Advised blocks fault once per
// 2 MiB instead (5,600 faults in all).
#pragma once

#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace radquad {

inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// `bytes` rounded up to whole huge pages: what allocateHugePages(bytes) holds.
constexpr std::size_t hugePageRounded(std::size_t bytes) {
  return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

// At least `bytes` bytes (rounded up to whole huge pages), aligned to a huge page and
// advised as huge pages; throws std::bad_alloc when the memory is not there. Uninitialised.
void* allocateHugePages(std::size_t bytes);
void freeHugePages(void* memory) noexcept;

// A standard allocator that takes requests of a huge page or more from allocateHugePages and
// smaller ones from operator new (a small array gains nothing from a 2 MiB block).
template <class T>
class HugePageAllocator {
 public:
  using value_type = T;

  HugePageAllocator() noexcept = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) return static_cast<T*>(allocateHugePages(bytes));
    return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
  }
  void deallocate(T* memory, std::size_t n) noexcept {
    if (n * sizeof(T) >= kHugePageBytes) {
      freeHugePages(memory);
    } else {
      ::operator delete(memory, std::align_val_t(alignof(T)));
    }
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

// The solver's arrays of one entry per link (millions at degree 2).
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace radquad
