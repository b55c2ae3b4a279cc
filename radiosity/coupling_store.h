// The coupling matrices of the solver's links, F x F doubles each (column-major, F the
// number of basis functions), kept in large blocks instead of one heap allocation per link.
// A cubic-basis solve holds about 10^5 links of 2 KiB each: separate allocations cost more
// than a small adaptive rule's kernel evaluations (allocator work and a first-touch page fault
// every other link), and scatter the matrices the gathers stream through in every iteration.
// Blocks never move, so a slot's address is stable while the store grows.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

namespace radquad {

class CouplingStore {
 public:
  explicit CouplingStore(int functions);

  // Makes slots 0 .. links - 1 available (new slots are zero).
  void resize(std::size_t links);
  std::size_t size() const { return size_; }

  Eigen::Map<Eigen::MatrixXd> operator[](std::size_t link) {
    return Eigen::Map<Eigen::MatrixXd>(slot(link), functions_, functions_);
  }
  const double* data(std::size_t link) const { return slot(link); }

 private:
  struct FreeBlock {
    void operator()(double* block) const;
  };
  // The blocks are owned by the store; a const store hands out read-only pointers (data).
  double* slot(std::size_t link) const {
    return blocks_[link / slotsPerBlock_].get() + (link % slotsPerBlock_) * slotSize_;
  }

  int functions_;
  std::size_t slotSize_;       // F * F
  std::size_t slotsPerBlock_;  // slots in one block of kBlockBytes
  std::size_t size_ = 0;
  std::vector<std::unique_ptr<double[], FreeBlock>> blocks_;
};

}  // namespace radquad
