#include "quadrature/estimate.h"

#include <cmath>

#include "kernel/input_error.h"

namespace radquad {

void EntrywiseMoments::add(const Eigen::MatrixXd& value) {
  ++count_;
  if (count_ == 1) {
    mean_ = value;
    squares_ = Eigen::MatrixXd::Zero(value.rows(), value.cols());
    return;
  }
  RADQUAD_REQUIRE(value.rows() == mean_.rows() && value.cols() == mean_.cols());
  const Eigen::MatrixXd delta = value - mean_;
  mean_ += delta / double(count_);
  squares_ += delta.cwiseProduct(value - mean_);
}

Eigen::MatrixXd EntrywiseMoments::sampleDeviation() const {
  if (count_ < 2) return Eigen::MatrixXd::Zero(mean_.rows(), mean_.cols());
  // Each added term is a product of two same-signed differences, so S_n >= 0 up to
  // rounding; the clamp keeps a rounded -0 from a square root.
  return (squares_ / double(count_ - 1)).cwiseMax(0.0).cwiseSqrt();
}

Eigen::MatrixXd EntrywiseMoments::standardError() const {
  return sampleDeviation() / std::sqrt(double(count_ < 1 ? 1 : count_));
}

}  // namespace radquad
