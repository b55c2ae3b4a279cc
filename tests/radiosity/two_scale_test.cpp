// The two-scale relations of the orthonormal Legendre basis: push is exact (the child's
// polynomial equals the parent's on the child), push then pull is the identity, and pull
// conserves the integral of the radiosity over the element.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernel/legendre_basis.h"
#include "radiosity/two_scale.h"

namespace radquad {
namespace {

Coefficients randomCoefficients(int degree, unsigned seed) {
  std::mt19937 generator(seed);  // raw engine output is specified by the standard
  Coefficients c(basisFunctionCount(degree), 3);
  for (int a = 0; a < c.rows(); ++a)
    for (int k = 0; k < 3; ++k) c(a, k) = double(generator()) / double(generator.max()) - 0.5;
  return c;
}

// The unit-square polynomial sum_a b_a phi_a(u, v) (the 1/sqrt(A) factor left out).
double evaluate(const Coefficients& c, int channel, int degree, double u, double v) {
  double values[basisFunctionCount(kMaxBasisDegree)];
  tensorBasisValues(degree, u, v, values);
  double sum = 0.0;
  for (int a = 0; a < c.rows(); ++a) sum += c(a, channel) * values[a];
  return sum;
}

class TwoScaleTest : public ::testing::TestWithParam<int> {};

TEST_P(TwoScaleTest, PushReproducesTheParentPolynomialOnEachChild) {
  const int degree = GetParam();
  const TwoScale twoScale(degree);
  const Coefficients parent = randomCoefficients(degree, 7u + unsigned(degree));
  for (int c = 0; c < 4; ++c) {
    const Coefficients child = twoScale.push(parent, c);
    for (double s : {0.1, 0.5, 0.93}) {
      for (double t : {0.2, 0.77}) {
        const double u = (c / 2 + s) / 2, v = (c % 2 + t) / 2;
        // B = p_P(u,v)/sqrt(A) = p_C(s,t)/sqrt(A/4): p_C = p_P / 2.
        EXPECT_NEAR(evaluate(child, 1, degree, s, t), 0.5 * evaluate(parent, 1, degree, u, v),
                    1e-12)
            << "degree " << degree << " child " << c;
      }
    }
  }
}

TEST_P(TwoScaleTest, PushThenPullIsTheIdentity) {
  const int degree = GetParam();
  const TwoScale twoScale(degree);
  const Coefficients parent = randomCoefficients(degree, 11u + unsigned(degree));
  Coefficients pulled = Coefficients::Zero(parent.rows(), 3);
  for (int c = 0; c < 4; ++c) twoScale.pullAdd(twoScale.push(parent, c), c, pulled);
  EXPECT_LT((pulled - parent).cwiseAbs().maxCoeff(), 1e-13) << "degree " << degree;
}

TEST_P(TwoScaleTest, PullConservesEnergy) {
  const int degree = GetParam();
  const TwoScale twoScale(degree);
  // Arbitrary (discontinuous) children on a parent of area 4 (children of area 1):
  // int B dA = sqrt(A) b_0 on every element.
  const double parentArea = 4.0, childArea = 1.0;
  Coefficients pulled = Coefficients::Zero(basisFunctionCount(degree), 3);
  Eigen::RowVector3d childEnergy = Eigen::RowVector3d::Zero();
  for (int c = 0; c < 4; ++c) {
    const Coefficients child = randomCoefficients(degree, 100u * unsigned(c) + unsigned(degree));
    childEnergy += std::sqrt(childArea) * child.row(0);
    twoScale.pullAdd(child, c, pulled);
  }
  const Eigen::RowVector3d parentEnergy = std::sqrt(parentArea) * pulled.row(0);
  EXPECT_LT((parentEnergy - childEnergy).cwiseAbs().maxCoeff(), 1e-13) << "degree " << degree;
}

INSTANTIATE_TEST_SUITE_P(Degrees, TwoScaleTest, ::testing::Values(0, 1, 2, 3));

}  // namespace
}  // namespace radquad
