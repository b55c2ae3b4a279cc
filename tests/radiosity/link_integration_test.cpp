// The solver's link integration near the kernel's singularity: the composite rule over the
// quadrant pieces (radiosity/link_integration.h) against an independent assembly of the
// pieces' own couplings with the two-scale matrices, and its form factor against Howell's
// closed form for perpendicular squares sharing an edge.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "kernel/legendre_basis.h"
#include "quadrature/adaptive_gauss.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/link_integration.h"
#include "radiosity/two_scale.h"
#include "radiosity/visibility.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

Patch quadrantOf(const Patch& patch, int c) {
  return Patch::make(patch.origin + (c / 2) * 0.5 * patch.edgeU + (c % 2) * 0.5 * patch.edgeV,
                     0.5 * patch.edgeU, 0.5 * patch.edgeV, "quadrant");
}

// The pieces' own couplings, each from the product rule on the sub-elements with their own
// basis, put together as K = sum_{c, c'} T_c^T K_(c, c') T_c' (radiosity/two_scale.h).
Eigen::MatrixXd assembleWithTwoScale(const Patch& receiver, const Patch& source,
                                     const GaussPointCounts& rule, const GaussTables& tables,
                                     const TwoScale& twoScale, int depth) {
  if (depth <= 0 || !elementsNear(receiver, source)) {
    const GaussSide& r = tables.side(rule[0], rule[1]);
    const GaussSide& s = tables.side(rule[2], rule[3]);
    CouplingAccumulator accumulator;
    LinkIntegral integral;
    accumulator.product(Link{receiver, source, nullptr}, r.samples, r.basis, s.samples, s.basis,
                        integral);
    return integral.coupling;
  }
  const int functions = int(twoScale.child(0).rows());
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(functions, functions);
  for (int cr = 0; cr < 4; ++cr) {
    const Patch receiverQuadrant = quadrantOf(receiver, cr);
    for (int cs = 0; cs < 4; ++cs) {
      const Patch sourceQuadrant = quadrantOf(source, cs);
      if (!mayExchange(receiverQuadrant, sourceQuadrant)) continue;
      total += twoScale.child(cr).transpose() *
               assembleWithTwoScale(receiverQuadrant, sourceQuadrant, rule, tables, twoScale,
                                    depth - 1) *
               twoScale.child(cs);
    }
  }
  return total;
}

// Two unit squares at a right angle sharing the edge along x: the floor z = 0 (normal +z)
// and the wall y = 0 (normal +y).
const Patch kFloor = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "floor");
const Patch kWall = Patch::make({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, "wall");

class NearLinkTest : public ::testing::TestWithParam<int> {};

TEST_P(NearLinkTest, CompositeRuleEqualsTheTwoScaleAssemblyOfThePieces) {
  const int degree = GetParam();
  const GaussTables tables(degree);
  const TwoScale twoScale(degree);
  const int functions = basisFunctionCount(degree);
  for (const GaussPointCounts& rule :
       {GaussPointCounts{degree + 1, degree + 1, degree + 1, degree + 1},
        GaussPointCounts{degree + 1, degree + 1, 1, 2}, GaussPointCounts{3, 2, 2, 1}}) {
    for (int depth : {0, 1, 3}) {
      Eigen::MatrixXd composite(functions, functions);
      LinkIntegrator integrator;
      const LinkIntegrationCounts counts =
          integrator.integrate(Link{kFloor, kWall, nullptr}, rule, tables, depth,
                               Eigen::Map<Eigen::MatrixXd>(composite.data(), functions, functions));
      const Eigen::MatrixXd assembled =
          assembleWithTwoScale(kFloor, kWall, rule, tables, twoScale, depth);
      const double scale = assembled.cwiseAbs().maxCoeff();
      EXPECT_LT((composite - assembled).cwiseAbs().maxCoeff(), 1e-12 * scale)
          << "degree " << degree << " depth " << depth;
      EXPECT_GT(counts.kernelEvaluations, 0u);
      EXPECT_EQ(counts.kernelEvaluations % ruleEvaluations(rule), 0u);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, NearLinkTest, ::testing::Values(0, 1, 2, 3));

// The shared edge makes the kernel unbounded: a product rule over the whole pair is far off
// (Howell C-14: F = 0.2000437 for unit squares), and the error comes from the pieces that
// still touch the edge, whose size halves with each subdivision level: the error must halve.
TEST(NearLink, SubdivisionConvergesToTheSharedEdgeFormFactor) {
  const double exact = analytic::perpendicularRectangles(1.0, 1.0, 1.0);
  const GaussTables tables(0);
  double previousError = INFINITY;
  for (int depth = 0; depth <= 4; ++depth) {
    double k = 0.0;
    LinkIntegrator integrator;
    integrator.integrate(Link{kFloor, kWall, nullptr}, {4, 4, 4, 4}, tables, depth,
                         Eigen::Map<Eigen::MatrixXd>(&k, 1, 1));
    const double formFactor = k;  // unit areas: F = K[0][0] sqrt(A_s / A_r)
    const double error = std::abs(formFactor - exact);
    if (depth > 0) {
      EXPECT_NEAR(error / previousError, 0.5, 0.05) << "depth " << depth;
    }
    previousError = error;
  }
}

}  // namespace
}  // namespace radquad
