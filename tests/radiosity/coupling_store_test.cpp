// The solver's coupling store: slots keep their values and addresses while it grows, widths
// are independent, released slots are reused by their own width only, and the memory held
// follows the widths in use.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "radiosity/coupling_store.h"
#include "radiosity/huge_pages.h"

namespace radquad {
namespace {

constexpr std::size_t kBlockBytes = std::size_t(2) << 20;  // a huge page, radiosity/huge_pages.h

TEST(CouplingStore, SlotsKeepTheirValuesAndAddressesAsTheStoreGrows) {
  for (int functions : {1, 9, 16}) {
    for (int columns : {1, functions}) {
      CouplingStore store(functions);
      const std::size_t values = std::size_t(functions * columns);
      std::vector<int> slots;
      for (int k = 0; k < 3; ++k) slots.push_back(store.allocate(columns));
      EXPECT_EQ(store.slots(columns), 3u);
      for (std::size_t v = 0; v < values; ++v) EXPECT_EQ(store.data(columns, slots[2])[v], 0.0f);
      for (std::size_t v = 0; v < values; ++v) store.data(columns, slots[1])[v] = 1.5;
      const float* first = store.data(columns, slots[1]);
      // Past three blocks, so that blocks are added.
      const std::size_t count = 3 * (kBlockBytes / (sizeof(float) * values)) + 5;
      while (slots.size() < count) slots.push_back(store.allocate(columns));
      EXPECT_EQ(store.slots(columns), count);
      for (std::size_t k = 0; k < count; k += 97) {
        store.data(columns, slots[k])[values - 1] = float(k);
      }
      EXPECT_EQ(store.data(columns, slots[1]), first);
      EXPECT_EQ(store.data(columns, slots[1])[0], 1.5f);
      for (std::size_t k = 97; k < count; k += 97) {
        EXPECT_EQ(store.data(columns, slots[k])[values - 1], float(k)) << k;
      }
      // Distinct slots do not overlap: neighbours are exactly one slot apart or in other
      // blocks.
      for (std::size_t k = 1; k < count; ++k) {
        const float* a = store.data(columns, slots[k - 1]);
        const float* b = store.data(columns, slots[k]);
        EXPECT_TRUE(b >= a + values || a >= b + values) << k;
      }
    }
  }
}

TEST(CouplingStore, ReleasedSlotsAreReusedByTheirOwnWidthOnly) {
  CouplingStore store(16);
  const int narrow = store.allocate(2), wide = store.allocate(16);
  const int other = store.allocate(2);
  EXPECT_NE(narrow, other);
  store.release(2, narrow);
  EXPECT_EQ(store.allocate(16), wide + 1);  // another width: a new slot
  EXPECT_EQ(store.allocate(2), narrow);      // its own width: the released one
  EXPECT_EQ(store.allocate(2), other + 1);   // then new ones again
  EXPECT_EQ(store.slots(2), 3u);
  EXPECT_EQ(store.slots(16), 2u);
  EXPECT_EQ(store.slots(1), 0u);
}

TEST(CouplingStore, MemoryFollowsTheWidthsInUse) {
  // 10,000 one-column slots of a cubic basis take 16 x 4 bytes each (single precision): one
  // 2 MiB block; as many full ones (1 KiB each, 2,048 to a block) take 5 blocks.
  CouplingStore narrow(16), full(16);
  EXPECT_EQ(narrow.bytes(), 0u);
  for (int k = 0; k < 10000; ++k) {
    narrow.allocate(1);
    full.allocate(16);
  }
  EXPECT_EQ(narrow.bytes(), kBlockBytes);
  EXPECT_EQ(full.bytes(), 5 * kBlockBytes);
}

// The solver's link array grows through HugePageAllocator: arrays of a huge page and more sit
// at huge-page boundaries, smaller ones are ordinary allocations, and the contents survive every
// reallocation across the threshold (both ways, through shrink_to_fit).
TEST(HugePageAllocator, LargeArraysAreHugePageAlignedAndGrowthKeepsTheirContents) {
  EXPECT_EQ(hugePageRounded(1), kBlockBytes);
  EXPECT_EQ(hugePageRounded(kBlockBytes), kBlockBytes);
  EXPECT_EQ(hugePageRounded(kBlockBytes + 1), 2 * kBlockBytes);
  struct Item {
    std::uint64_t index;
    std::vector<int> payload;  // moved, not copied, as the vector grows
  };
  std::vector<Item, HugePageAllocator<Item>> items;
  const std::size_t count = 3 * kBlockBytes / sizeof(Item) + 7;
  bool sawSmall = false, sawLarge = false;
  for (std::size_t k = 0; k < count; ++k) {
    items.push_back({k, std::vector<int>(1 + k % 3, int(k))});
    const bool large = items.capacity() * sizeof(Item) >= kBlockBytes;
    (large ? sawLarge : sawSmall) = true;
    if (large) {
      ASSERT_EQ(reinterpret_cast<std::uintptr_t>(items.data()) % kBlockBytes, 0u) << k;
    }
  }
  EXPECT_TRUE(sawSmall);
  EXPECT_TRUE(sawLarge);
  items.resize(10);
  items.shrink_to_fit();
  EXPECT_LT(items.capacity() * sizeof(Item), kBlockBytes);
  for (std::size_t k = 0; k < items.size(); ++k) {
    EXPECT_EQ(items[k].index, k);
    EXPECT_EQ(items[k].payload, std::vector<int>(1 + k % 3, int(k)));
  }
  std::vector<Item, HugePageAllocator<Item>> copy(count / 2, Item{7, {1, 2}});
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(copy.data()) % kBlockBytes, 0u);
  EXPECT_EQ(copy.back().payload, (std::vector<int>{1, 2}));
}

}  // namespace
}  // namespace radquad
