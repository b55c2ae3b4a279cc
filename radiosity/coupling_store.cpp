#include "radiosity/coupling_store.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

namespace radquad {
namespace {

// One block is one 2 MiB huge page where the kernel grants them (madvise below): the first
// touch of a block then costs one page fault instead of 512.
constexpr std::size_t kBlockBytes = std::size_t(2) << 20;

}  // namespace

void CouplingStore::FreeBlock::operator()(double* block) const {
  std::free(block);
}

CouplingStore::CouplingStore(int functions)
    : functions_(functions),
      slotSize_(std::size_t(functions) * std::size_t(functions)),
      slotsPerBlock_(std::max<std::size_t>(1, kBlockBytes / (slotSize_ * sizeof(double)))) {}

void CouplingStore::resize(std::size_t links) {
  const std::size_t blockBytes = slotsPerBlock_ * slotSize_ * sizeof(double);
  const std::size_t allocation = (blockBytes + kBlockBytes - 1) / kBlockBytes * kBlockBytes;
  while (blocks_.size() * slotsPerBlock_ < links) {
    void* memory = std::aligned_alloc(kBlockBytes, allocation);
    if (memory == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(memory, allocation, MADV_HUGEPAGE);  // advisory: ignored where unsupported
#endif
    // Touch the block now, so that its page faults are paid here rather than by whichever
    // link is integrated first into it.
    std::memset(memory, 0, allocation);
    blocks_.emplace_back(static_cast<double*>(memory));
  }
  size_ = std::max(size_, links);
}

}  // namespace radquad
