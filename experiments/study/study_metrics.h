// The error metrics of the study (docs/design.md, "The study") and their summary statistics.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <vector>

namespace radquad {

// Figure 1: |K~[0][0] - K[0][0]| / K[0][0].
double relativeError(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& reference);

// A scale-free error of the whole coupling: ||K~ - K||_F / ||K||_F (Frobenius norms), so
// that links of very different transfer (a touching pair, a distant one) and the classes can
// be compared; U_b is an absolute error per unit area and follows the link's size of K.
double relativeFrobeniusError(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& reference);

// Figure 2: for each source function b (its coefficient 1, the others 0), the upper bound on
// the L1 error per unit receiver area
//   U_b = (1/A_r) sum_a |K~[a][b] - K[a][b]| int_{A_r} |M_a| dA,
// with int |M_(i,j)| dA = sqrt(A_r) c_i c_j and c_k = legendreAbsoluteIntegral(k).
// `difference` = K~ - K of a degree-d coupling ((d+1)^2 square); returns (d+1)^2 values.
std::vector<double> l1ErrorBound(const Eigen::MatrixXd& difference, double receiverArea);

struct SummaryStatistics {
  double mean = 0.0;
  double median = 0.0;
  double p90 = 0.0;  // linear interpolation between order statistics at q (n - 1)
  double max = 0.0;
  double sem = 0.0;  // sample standard deviation / sqrt(n); 0 for n < 2
  // The largest value's share of the sum: how much of the mean one link carries
  // (study_statistics.h, largestShare); 0 when the sum is 0.
  double largestShare = 0.0;
  std::size_t count = 0;
};

SummaryStatistics summarize(std::vector<double> values);

// The sum of the values (a link's L1 bounds over its source functions: its U_tot).
double sum(const std::vector<double>& values);

nlohmann::json statisticsToJson(const SummaryStatistics& statistics);

}  // namespace radquad
