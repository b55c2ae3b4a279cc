// The memory budget's measure: the resident memory grows by what the process touches.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "radiosity/memory_budget.h"

namespace radquad {
namespace {

TEST(MemoryBudget, ResidentMemoryGrowsByTheBytesTouched) {
  constexpr std::size_t kBytes = std::size_t(64) << 20;
  const std::size_t before = residentBytes();
  ASSERT_GT(before, 0u);
  std::unique_ptr<char[]> block(new char[kBytes]);
  std::memset(block.get(), 1, kBytes);  // every page touched
  asm volatile("" : : "r"(block.get()) : "memory");  // the stores happen before the reading
  const std::size_t after = residentBytes();
  EXPECT_GE(after, before + kBytes / 4 * 3);
  EXPECT_LE(after, before + 2 * kBytes);
}

TEST(MemoryBudget, TheDefaultIsThreeQuartersOfTheMemoryLimit) {
  const std::size_t physical = physicalMemoryBytes();
  ASSERT_GT(physical, std::size_t(256) << 20);
  const std::size_t limit = memoryLimitBytes();
  EXPECT_GT(limit, 0u);
  EXPECT_LE(limit, physical);
  const std::size_t budget = defaultMemoryBudget();
  EXPECT_GE(budget, std::size_t(1) << 30);
  if (limit >= (std::size_t(4) << 30)) {
    EXPECT_EQ(budget, limit / 4 * 3);
  }
}

}  // namespace
}  // namespace radquad
