// What a receiver point sees of the source, as the exact gold's inner integrals take it
// (exact_visibility.h): signed rings and signed edge pieces in the source's parameter square.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <vector>

#include "reference/convex_polygons.h"

namespace radquad {

// What x sees: integrate f over V as sum_r sign(r) * (signed integral of f over ring(r)),
// r < count(), plus the pieces of an outline: sum_s segmentSign(s) * (the contour term of
// the edge segmentStart(s) -> segmentEnd(s)), s < segmentCount(). Both integrals the gold
// takes (Lambert's formula and the polar one) are sums of one term per edge, so a region
// bounded by pieces that close up only together (the outline of the shadows' union, cut at
// the points where the shadows cross) needs no rings. The storage is kept across clear()
// so that a thread reuses it.
class VisibleRings {
 public:
  std::size_t count() const { return count_; }
  bool empty() const { return count_ == 0 && segmentCount_ == 0; }
  const SourceRing& ring(std::size_t r) const { return rings_[r]; }
  double sign(std::size_t r) const { return signs_[r]; }
  void setSign(std::size_t r, double sign) { signs_[r] = sign; }
  void clear() {
    count_ = 0;
    segmentCount_ = 0;
  }
  // A new empty ring of the given sign (+1 for S', -1 for the rings of the shadows' union).
  SourceRing& add(double sign) {
    if (count_ == rings_.size()) {
      rings_.emplace_back();
      signs_.push_back(0.0);
    }
    rings_[count_].clear();
    signs_[count_] = sign;
    return rings_[count_++];
  }
  void add(const SourceRing& ring, double sign) { add(sign) = ring; }
  // Drops the first ring (S', the source in front of x: what is left is minus the shadows'
  // union, ExactVisibility); the rings keep their order and storage.
  void dropFirst() {
    if (count_ == 0) return;
    std::rotate(rings_.begin(), rings_.begin() + 1, rings_.begin() + std::ptrdiff_t(count_));
    std::rotate(signs_.begin(), signs_.begin() + 1, signs_.begin() + std::ptrdiff_t(count_));
    --count_;
  }
  // Drops the rings from `count` on (their storage is kept).
  void truncate(std::size_t count) { count_ = std::min(count, count_); }

  std::size_t segmentCount() const { return segmentCount_; }
  // Drops the segments from `count` on.
  void truncateSegments(std::size_t count) { segmentCount_ = std::min(count, segmentCount_); }
  const Eigen::Vector2d& segmentStart(std::size_t s) const { return segmentEnds_[2 * s]; }
  const Eigen::Vector2d& segmentEnd(std::size_t s) const { return segmentEnds_[2 * s + 1]; }
  double segmentSign(std::size_t s) const { return segmentSigns_[s]; }
  void addSegment(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double sign) {
    if (segmentCount_ == segmentSigns_.size()) {
      segmentEnds_.resize(2 * segmentCount_ + 2);
      segmentSigns_.push_back(0.0);
    }
    segmentEnds_[2 * segmentCount_] = start;
    segmentEnds_[2 * segmentCount_ + 1] = end;
    segmentSigns_[segmentCount_++] = sign;
  }

 private:
  std::vector<SourceRing> rings_;
  std::vector<double> signs_;
  std::size_t count_ = 0;
  std::vector<Eigen::Vector2d> segmentEnds_;  // start, end of each segment
  std::vector<double> segmentSigns_;
  std::size_t segmentCount_ = 0;
};

}  // namespace radquad
