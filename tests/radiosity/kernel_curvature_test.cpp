// The kernel check of the adaptive rules (radiosity/kernel_curvature.h): its estimate of the
// midpoint rule's relative error along one source axis against that error computed
// independently, by a 40-point Gauss-Legendre rule along the axis (from the receiver's centre,
// through the source's centre), on a parallel, a perpendicular and a skew pair at several
// distances; and the cases where the source's centre sees nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrature/gauss_legendre.h"
#include "kernel/coupling.h"
#include "radiosity/kernel_curvature.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

// (int_{-1/2}^{1/2} G(x, c + t e) dt - G(x, c)) / G(x, c), x the receiver's centre.
double trueMidpointError(const Patch& receiver, const Patch& source, bool alongU) {
  const GaussLegendreRule& rule = gaussLegendreUnit(40);
  const Vec x = receiver.centre(), c = source.centre();
  const Vec e = alongU ? source.edgeU : source.edgeV;
  double integral = 0.0;
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
    integral += rule.weights[i] * unoccludedKernel(receiver, x, source, c + (rule.nodes[i] - 0.5) * e);
  }
  const double midpoint = unoccludedKernel(receiver, x, source, c);
  return (integral - midpoint) / midpoint;
}

TEST(KernelCurvatureTest, EstimateFollowsTheMidpointRulesError) {
  const Patch source = Patch::make(Vec::Zero(), Vec(1, 0, 0), Vec(0, 1, 0), "source");
  int compared = 0;
  for (double distance : {1.0, 2.0, 4.0, 8.0}) {
    const Patch parallel = Patch::make(Vec(0, 1, distance), Vec(1, 0, 0), Vec(0, -1, 0), "parallel");
    const Patch perpendicular =
        Patch::make(Vec(0, distance, 0.2), Vec(1, 0, 0), Vec(0, 0, 1), "perpendicular");
    const Patch skew = Patch::make(Vec(0.3, distance, distance), Vec(1, 0, 0.2),
                                   Vec(0, -0.8, 0.6), "skew");
    const char* names[] = {"parallel", "perpendicular", "skew"};
    const Patch* receivers[] = {&parallel, &perpendicular, &skew};
    for (int k = 0; k < 3; ++k) {
      const Patch* receiver = receivers[k];
      for (bool alongU : {true, false}) {
        const double truth = std::abs(trueMidpointError(*receiver, source, alongU));
        const double estimate = midpointRelativeError(*receiver, source, alongU);
        // Simpson's correction is the leading term of the error: within 25% where the
        // error is small enough to matter for the check, and always of the same size.
        if (truth < 0.05 && truth > 1e-6) {
          EXPECT_NEAR(estimate, truth, 0.25 * truth) << names[k] << " " << distance;
          ++compared;
        } else if (truth >= 0.05) {
          EXPECT_GT(estimate, 0.3 * truth) << names[k] << " " << distance;
        }
      }
    }
  }
  EXPECT_GE(compared, 12);
}

TEST(KernelCurvatureTest, ErrorShrinksLikeTheSquareOfSizeOverDistance) {
  const Patch source = Patch::make(Vec::Zero(), Vec(1, 0, 0), Vec(0, 1, 0), "source");
  const Patch near = Patch::make(Vec(0, 1, 4), Vec(1, 0, 0), Vec(0, -1, 0), "near");
  const Patch far = Patch::make(Vec(0, 1, 8), Vec(1, 0, 0), Vec(0, -1, 0), "far");
  const double ratio = midpointRelativeError(near, source, true) / midpointRelativeError(far, source, true);
  EXPECT_NEAR(ratio, 4.0, 0.4);
}

TEST(KernelCurvatureTest, SourceCentreBehindTheReceiversPlaneIsTheWorstCase) {
  // A receiver in the plane z = 0.5 facing down (-z), beside a source that rises through
  // that plane: the source's centre at z = 0.6 is behind it, its lower edge at z = 0 in
  // front.
  const Patch receiver = Patch::make(Vec(0, 0, 0.5), Vec(0, 1, 0), Vec(1, 0, 0), "receiver");
  ASSERT_LT(receiver.normal.z(), 0.0);
  const Patch source = Patch::make(Vec(2, 0, 0), Vec(0, 0, 1.2), Vec(0, 1, 0), "source");
  ASSERT_LT(source.normal.x(), 0.0);  // facing the receiver
  EXPECT_EQ(midpointRelativeError(receiver, source, true), 1.0);
  // Along the axis that stays behind the plane nothing is seen at all: 0.
  EXPECT_EQ(midpointRelativeError(receiver, source, false), 0.0);
}

}  // namespace
}  // namespace radquad
