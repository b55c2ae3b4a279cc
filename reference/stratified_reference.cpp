#include "reference/stratified_reference.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "kernel/input_error.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/random/seeds.h"
#include "quadrature/rules/stratified.h"

namespace radquad {
namespace {

struct Draws {
  std::vector<LinkIntegral> integrals;
};

Draws drawReplicates(const Link& link, int degree, std::uint64_t seed, int strataPerAxis,
                     int replicates, std::uint32_t firstIndex) {
  if (strataPerAxis < 1 || strataPerAxis > 56) {
    throw InputError("reference: strata per axis " + std::to_string(strataPerAxis) +
                     " is out of range: expected 1..56");
  }
  if (replicates < 2 || replicates > 100000) {
    throw InputError("reference: " + std::to_string(replicates) +
                     " replicates cannot estimate a standard error: expected 2..100000");
  }
  const PreparedRule prepared(std::make_shared<StratifiedRule>(strataPerAxis), degree);
  CouplingAccumulator accumulator;
  Draws draws;
  draws.integrals.resize(std::size_t(replicates));
  for (int j = 0; j < replicates; ++j) {
    prepared.integrate(link, replicateSeed(seed, firstIndex + std::uint32_t(j)), accumulator,
                       draws.integrals[std::size_t(j)]);
  }
  return draws;
}

// Entrywise sample standard deviation (denominator R-1) of the draws.
void spread(const Draws& draws, Eigen::MatrixXd& mean, Eigen::MatrixXd& deviation,
            double& formFactorMean, double& formFactorDeviation) {
  const double count = double(draws.integrals.size());
  mean =
      Eigen::MatrixXd::Zero(draws.integrals[0].coupling.rows(), draws.integrals[0].coupling.cols());
  formFactorMean = 0.0;
  for (const auto& draw : draws.integrals) {
    mean += draw.coupling;
    formFactorMean += draw.formFactor;
  }
  mean /= count;
  formFactorMean /= count;
  Eigen::MatrixXd squares = Eigen::MatrixXd::Zero(mean.rows(), mean.cols());
  double formFactorSquares = 0.0;
  for (const auto& draw : draws.integrals) {
    squares += (draw.coupling - mean).cwiseAbs2();
    formFactorSquares += (draw.formFactor - formFactorMean) * (draw.formFactor - formFactorMean);
  }
  deviation = (squares / (count - 1.0)).cwiseSqrt();
  formFactorDeviation = std::sqrt(formFactorSquares / (count - 1.0));
}

}  // namespace

ReferenceEstimate stratifiedReference(const Link& link, int degree, std::uint64_t seed,
                                      const ReferenceOptions& options) {
  const Draws draws =
      drawReplicates(link, degree, seed, options.strataPerAxis, options.replicates, 0);
  ReferenceEstimate estimate;
  estimate.integral = draws.integrals[0];
  estimate.replicates = options.replicates;
  Eigen::MatrixXd mean;
  double formFactorMean = 0.0;
  spread(draws, mean, estimate.couplingStandardError, formFactorMean,
         estimate.formFactorStandardError);
  for (const auto& draw : draws.integrals)
    estimate.totalKernelEvaluations += draw.kernelEvaluations;
  return estimate;
}

ReplicateMean stratifiedReplicateMean(const Link& link, int degree, std::uint64_t seed,
                                      int strataPerAxis, int replicates, std::uint32_t firstIndex) {
  const Draws draws = drawReplicates(link, degree, seed, strataPerAxis, replicates, firstIndex);
  ReplicateMean result;
  Eigen::MatrixXd deviation;
  double formFactorDeviation = 0.0;
  spread(draws, result.coupling, deviation, result.formFactor, formFactorDeviation);
  // The standard error of a mean of R independent draws.
  const double root = std::sqrt(double(replicates));
  result.couplingStandardError = deviation / root;
  result.formFactorStandardError = formFactorDeviation / root;
  for (const auto& draw : draws.integrals) {
    result.kernelEvaluations += draw.kernelEvaluations;
    result.raysCast += draw.raysCast;
    result.raysBlocked += draw.raysBlocked;
  }
  return result;
}

}  // namespace radquad
