#include "radiosity/huge_pages.h"

#include <sys/mman.h>

#include <cstdlib>

namespace radquad {

void* allocateHugePages(std::size_t bytes) {
  if (bytes > std::numeric_limits<std::size_t>::max() - kHugePageBytes) throw std::bad_alloc();
  const std::size_t rounded = bytes == 0 ? kHugePageBytes : hugePageRounded(bytes);
  void* memory = std::aligned_alloc(kHugePageBytes, rounded);
  if (memory == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  madvise(memory, rounded, MADV_HUGEPAGE);  // advisory: ignored where unsupported
#endif
  return memory;
}

void freeHugePages(void* memory) noexcept { std::free(memory); }

}  // namespace radquad
