#include "radiosity/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace radquad {

std::size_t residentBytes() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (file == nullptr) return 0;
  unsigned long long size = 0, resident = 0;
  const int read = std::fscanf(file, "%llu %llu", &size, &resident);
  std::fclose(file);
  if (read != 2) return 0;
  const long page = sysconf(_SC_PAGESIZE);
  return page > 0 ? std::size_t(resident) * std::size_t(page) : 0;
}

std::size_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return std::size_t(pages) * std::size_t(page);
}

std::size_t memoryLimitBytes() {
  std::size_t limit = physicalMemoryBytes();
  // A control group's limit (v2, then v1), when there is one below the physical memory.
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::FILE* file = std::fopen(path, "r");
    if (file == nullptr) continue;
    unsigned long long value = 0;
    const int read = std::fscanf(file, "%llu", &value);
    std::fclose(file);
    if (read == 1 && value > 0 && (limit == 0 || value < limit)) limit = std::size_t(value);
  }
  return limit;
}

std::size_t defaultMemoryBudget() {
  constexpr std::size_t kGiB = std::size_t(1) << 30;
  const std::size_t physical = memoryLimitBytes();
  if (physical == 0) return 64 * kGiB;
  return std::max(kGiB, physical / 4 * 3);
}

}  // namespace radquad
