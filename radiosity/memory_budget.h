// The solver's memory budget: the process's resident memory, read from the operating system,
// against a limit (SolverOptions::maxMemoryBytes). Refinement and the coupling store are
// what grow with a scene; the solver compares after the initial links, after every wave of
// refinement and after every integration pass, and fails with a message naming the budget
// (exit status 3 from `radquad solve`) instead of being killed by the system.
#pragma once

#include <cstddef>

namespace radquad {

// Resident set size of this process in bytes (/proc/self/statm); 0 where it cannot be read.
std::size_t residentBytes();

// Physical memory of the machine in bytes; 0 where unknown.
std::size_t physicalMemoryBytes();

// The physical memory, or the process's control group limit (cgroup v2 memory.max, or v1
// memory.limit_in_bytes) where that is lower; 0 where unknown.
std::size_t memoryLimitBytes();

// Three quarters of memoryLimitBytes() (at least 1 GiB), or 64 GiB where it is unknown.
std::size_t defaultMemoryBudget();

}  // namespace radquad
