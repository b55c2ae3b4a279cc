// The estimate of a mean from independent draws: entrywise mean, sample standard deviation
// and standard error of matrices of one shape, accumulated one draw at a time. One type
// serves every place that summarises random draws: the paper reference's replicates, the
// dense stratified gold, the study's trials of a random rule and `radquad link --trials`.
//
// The update is Welford's: after n draws, mean_n = mean_{n-1} + (x - mean_{n-1}) / n and
// S_n = S_{n-1} + (x - mean_{n-1}) (x - mean_n), entry by entry, so that a deviation that is
// small against the mean is not lost to cancellation (the textbook sum of squares minus n
// mean^2 loses it). sampleDeviation() = sqrt(S_n / (n - 1)); standardError() divides it by
// sqrt(n), the standard error of the mean of the n draws. Both are zero for n < 2.
#pragma once

#include <Eigen/Core>
#include <cstddef>

namespace radquad {

class EntrywiseMoments {
 public:
  // The first draw fixes the shape; a later draw of another shape is an internal error.
  void add(const Eigen::MatrixXd& value);
  void add(double value) { add(Eigen::MatrixXd::Constant(1, 1, value)); }
  std::size_t count() const { return count_; }
  const Eigen::MatrixXd& mean() const { return mean_; }
  Eigen::MatrixXd sampleDeviation() const;
  Eigen::MatrixXd standardError() const;

 private:
  std::size_t count_ = 0;
  Eigen::MatrixXd mean_, squares_;
};

}  // namespace radquad
