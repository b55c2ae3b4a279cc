// The kernel against closed forms (Howell C-11, C-14), reciprocity and symmetry.
#include <gtest/gtest.h>

#include <cmath>

#include "kernel/coupling.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"
#include "tests/support/analytic_form_factors.h"
#include "tests/kernel/test_links.h"

namespace radquad {
namespace {

using testing::opposedReceiver;
using testing::opposedSource;
using analytic::parallelRectangles;
using testing::perpendicularReceiver;
using analytic::perpendicularRectangles;
using testing::perpendicularSource;

double formFactor(const Link& link, const std::string& rule, int degree = 0) {
  return PreparedRule(findRule(rule), degree).integrate(link).formFactor;
}

TEST(AnalyticFormFactors, HowellCatalogueValues) {
  // Published values: unit squares, opposed at distance 1: 0.1998; perpendicular with a
  // common edge: 0.2000 (Howell C-11, C-14; Cohen and Wallace 1993, table 4.1).
  EXPECT_NEAR(parallelRectangles(1, 1, 1), 0.1998249, 5e-8);
  EXPECT_NEAR(perpendicularRectangles(1, 1, 1), 0.2000438, 5e-7);
}

struct OpposedCase {
  double a, b, c;
};

class ParallelOpposed : public ::testing::TestWithParam<OpposedCase> {};

// The opposed-parallel kernel is smooth (analytic in all four variables), so a Gauss product
// converges geometrically: 8 points per axis reach 1e-7, FullGauss (3 per axis) 2e-3 at
// these aspect ratios and distances.
TEST_P(ParallelOpposed, GaussProductMatchesHowell) {
  const auto [a, b, c] = GetParam();
  const Link link{opposedReceiver(a, b), opposedSource(a, b, c), nullptr};
  const double exact = parallelRectangles(a, b, c);
  EXPECT_NEAR(formFactor(link, "Gauss:8x8x8x8"), exact, 1e-7 * exact)
      << "a=" << a << " b=" << b << " c=" << c;
  EXPECT_NEAR(formFactor(link, "FullGauss"), exact, 2e-3 * exact)
      << "a=" << a << " b=" << b << " c=" << c;
}

INSTANTIATE_TEST_SUITE_P(Kernel, ParallelOpposed,
                         ::testing::Values(OpposedCase{1, 1, 1}, OpposedCase{0.5, 2, 1.5},
                                           OpposedCase{0.2, 0.3, 1}, OpposedCase{2, 1, 4}));

// The shared edge puts the two patches in contact, where the kernel is singular; a Gauss
// product converges only algebraically. Near the edge the integrand along the edge is a peak
// as narrow as the distance to the edge, which n points per axis resolve only beyond a
// distance of about 1/n: the error falls like 1/n. Asserted: from 8 points per axis on, each
// doubling cuts the error by at least a quarter, and 64 points come within 7% of Howell.
TEST(PerpendicularSharedEdge, GaussProductConvergesToHowell) {
  const double l = 1.0, w = 0.7, h = 1.3;
  const Link link{perpendicularReceiver(l, w), perpendicularSource(l, h), nullptr};
  const double exact = perpendicularRectangles(w, h, l);
  double previousError = INFINITY;
  for (int n : {8, 16, 32, 64}) {
    const std::string rule = "Gauss:" + std::to_string(n) + "x" + std::to_string(n) + "x" +
                             std::to_string(n) + "x" + std::to_string(n);
    const double error = std::fabs(formFactor(link, rule) - exact) / exact;
    EXPECT_LT(error, 0.75 * previousError) << rule << ": error " << error;
    previousError = error;
  }
  EXPECT_LT(previousError, 0.07);
}

// The coupling from s to r is the transpose of the one from r to s (G is symmetric, and a
// product rule evaluates the same point pairs in either direction).
TEST(Coupling, ReciprocityTransposes) {
  const Patch r = Patch::make({0.1, -0.2, 0.0}, {1.1, 0.1, 0.0}, {-0.2, 0.8, 0.1}, "r");
  const Patch s = Patch::make({0.3, 0.9, 1.2}, {0.6, 0.0, -0.3}, {0.1, -0.9, 0.2}, "s");
  ASSERT_GT(r.normal.dot(s.centre() - r.centre()), 0.0);
  ASSERT_GT(s.normal.dot(r.centre() - s.centre()), 0.0);
  for (const char* rule : {"FullGauss", "Gauss:4x3x2x5"}) {
    // Gauss:RsxRtxSuxSv -> swap the receiver's and source's point counts for the reverse link.
    const std::string reverse =
        std::string(rule) == "FullGauss" ? std::string("FullGauss") : std::string("Gauss:2x5x4x3");
    for (int degree : {0, 2}) {
      const auto forward = PreparedRule(findRule(rule), degree).integrate(Link{r, s, nullptr});
      const auto backward = PreparedRule(findRule(reverse), degree).integrate(Link{s, r, nullptr});
      ASSERT_GT(forward.coupling(0, 0), 0.0);
      const double scale = forward.coupling.cwiseAbs().maxCoeff();
      EXPECT_LT((forward.coupling - backward.coupling.transpose()).cwiseAbs().maxCoeff(),
                1e-13 * scale)
          << rule << " degree " << degree;
      // Form factor reciprocity: A_r F_rs = A_s F_sr.
      EXPECT_NEAR(r.area * forward.formFactor, s.area * backward.formFactor,
                  1e-13 * r.area * forward.formFactor);
    }
  }
}

// With d = 0, K[0][0] = F sqrt(A_r/A_s) (docs/design.md).
TEST(Coupling, ConstantCouplingIsScaledFormFactor) {
  const Link link{opposedReceiver(0.5, 2), opposedSource(1.5, 0.4, 1), nullptr};
  const auto integral = PreparedRule(findRule("FullGauss"), 0).integrate(link);
  EXPECT_NEAR(integral.coupling(0, 0),
              integral.formFactor * std::sqrt(link.receiver.area / link.source.area), 1e-15);
}

// Back-facing pairs contribute nothing: a source behind the receiver's plane.
TEST(Coupling, ClampedCosinesGiveZeroBehind) {
  const Patch r = opposedReceiver(1, 1);
  const Patch behind = Patch::make({0, 1, -1}, {1, 0, 0}, {0, -1, 0}, "behind");
  const auto integral = PreparedRule(findRule("FullGauss"), 2).integrate(Link{r, behind, nullptr});
  EXPECT_EQ(integral.coupling.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(integral.kernelEvaluations, 81u);
}

// Unoccluded G at one pair against the textbook formula with explicit angles.
TEST(Kernel, PointKernelMatchesAngles) {
  const Patch r = opposedReceiver(1, 1);
  const Patch s = opposedSource(1, 1, 2);
  const Eigen::Vector3d x(0.2, 0.3, 0), y(0.9, 0.1, 2);
  const Eigen::Vector3d d = y - x;
  const double cosR = d.z() / d.norm(), cosS = d.z() / d.norm();
  EXPECT_NEAR(unoccludedKernel(r, x, s, y), cosR * cosS / (M_PI * d.squaredNorm()), 1e-16);
}

}  // namespace
}  // namespace radquad
