// The coupling matrices of the solver's links, kept in large blocks instead of one heap
// allocation per link. A link keeps F x c floats (column-major, F the number of basis
// functions, c <= F the columns it gathers through: radiosity/source_projection.h), so slots
// come in F widths, each width with its own blocks and its own list of released slots.
// Single precision: a coupling is integrated in double and rounded once when stored
// (relative 6e-8, far below any rule's quadrature error and the solve's tolerance of 1e-4);
// the gathers multiply in double. The gathers read every coupling in every iteration and are
// bound by memory, so half the bytes make them faster (cornell at degree 2: 8.4 s instead
// of 10.5 s, 0.86 GB instead of 1.29 GB; patch radiosities within 1.1e-8 relative, the same
// refinement).
// A cubic-basis solve holds about 5 x 10^5 links: separate allocations cost more than a small
// adaptive rule's kernel evaluations (allocator work and first-touch page faults), and
// scatter the matrices the gathers read in every iteration. Blocks never move, so a slot's
// address is stable while the store grows.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace radquad {

class CouplingStore {
 public:
  explicit CouplingStore(int functions);

  int functions() const { return functions_; }

  // A slot of F x columns floats (1 <= columns <= F): a released one of that width if any
  // (holding its old values), else a new one (zero). Returns its index within the width.
  int allocate(int columns);
  // Makes the slot available to the next allocate of the same width.
  void release(int columns, int slot);

  float* data(int columns, int slot) { return address(columns, slot); }
  const float* data(int columns, int slot) const { return address(columns, slot); }

  // Slots ever created of a width (in use or released), and the bytes of all blocks held.
  std::size_t slots(int columns) const { return widths_[std::size_t(columns - 1)].size; }
  std::size_t bytes() const;

 private:
  struct FreeBlock {
    void operator()(float* block) const;
  };
  struct Width {
    std::size_t slotSize = 0;       // F * columns
    std::size_t slotsPerBlock = 0;  // slots in one block
    std::size_t size = 0;           // slots created
    std::vector<std::unique_ptr<float[], FreeBlock>> blocks;
    std::vector<int> released;
  };
  // The blocks are owned by the store; a const store hands out read-only pointers.
  float* address(int columns, int slot) const {
    const Width& width = widths_[std::size_t(columns - 1)];
    return width.blocks[std::size_t(slot) / width.slotsPerBlock].get() +
           (std::size_t(slot) % width.slotsPerBlock) * width.slotSize;
  }

  int functions_;
  std::vector<Width> widths_;  // widths_[c - 1]: slots of c columns
};

}  // namespace radquad
