#include "radiosity/coupling_store.h"
#include "kernel/input_error.h"
#include "radiosity/huge_pages.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

namespace radquad {

void CouplingStore::FreeBlock::operator()(float* block) const {
  freeHugePages(block);
}

CouplingStore::CouplingStore(int functions) : functions_(functions) {
  widths_.resize(std::size_t(functions));
  for (int columns = 1; columns <= functions; ++columns) {
    Width& width = widths_[std::size_t(columns - 1)];
    width.slotSize = std::size_t(functions) * std::size_t(columns);
    width.slotsPerBlock = std::max<std::size_t>(1, kHugePageBytes / (width.slotSize * sizeof(float)));
  }
}

int CouplingStore::allocate(int columns) {
  RADQUAD_REQUIRE(columns >= 1 && columns <= functions_);
  Width& width = widths_[std::size_t(columns - 1)];
  if (!width.released.empty()) {
    const int slot = width.released.back();
    width.released.pop_back();
    return slot;
  }
  if (width.size == width.blocks.size() * width.slotsPerBlock) {
    const std::size_t blockBytes = width.slotsPerBlock * width.slotSize * sizeof(float);
    void* memory = allocateHugePages(blockBytes);
    // Touch the block now, so that its page faults are paid here rather than by whichever
    // link is integrated first into it.
    std::memset(memory, 0, hugePageRounded(blockBytes));
    width.blocks.emplace_back(static_cast<float*>(memory));
  }
  return int(width.size++);
}

void CouplingStore::release(int columns, int slot) {
  RADQUAD_REQUIRE(columns >= 1 && columns <= functions_);
  RADQUAD_REQUIRE(slot >= 0 && std::size_t(slot) < widths_[std::size_t(columns - 1)].size);
  widths_[std::size_t(columns - 1)].released.push_back(slot);
}

std::size_t CouplingStore::bytes() const {
  std::size_t total = 0;
  for (const Width& width : widths_) {
    const std::size_t blockBytes = width.slotsPerBlock * width.slotSize * sizeof(float);
    total += width.blocks.size() * hugePageRounded(blockBytes);
  }
  return total;
}

}  // namespace radquad
