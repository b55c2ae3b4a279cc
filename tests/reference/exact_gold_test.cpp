// The exact gold (reference/exact_gold.h) as a whole: against the dense stratified gold on
// occluded links and on a triangle soup, its error estimate against the true error, the
// unoccluded part apart against the whole integral, a grazing link, and determinism. Its
// pieces are tested in source_moments_test.cpp, exact_visibility_test.cpp and
// exact_visibility_contacts_test.cpp, its closed forms in exact_gold_closed_forms_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "kernel/occluder_scene.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"
#include "reference/gold_reference.h"
#include "tests/reference/gold_agreement.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

// The dense stratified gold (an independent, random method) and the exact gold agree within
// 5 of the dense gold's standard errors on every coefficient. The standard error comes from
// R = 64 replicates, so a correct gold's deviation over it follows Student's t with 63 degrees
// of freedom: P(|t_63| > 5) = 4.9e-6 per coefficient, 5e-4 over the test's 98
// coefficients. (With R = 8 the estimated error itself is too uncertain: P(|t_7| > 4) = 0.005
// per coefficient.)
void expectAgreesWithDenseGold(const Link& link, int degree) {
  GoldOptions dense;
  dense.method = GoldMethod::stratified;
  dense.denseStrata = 16;
  dense.denseReplicates = 64;
  const GoldReference stratified = goldReference(link, degree, 11, dense);
  ASSERT_EQ(stratified.method, "dense stratified");
  const ExactGold exact = exactGold(link, degree);
  EXPECT_TRUE(exact.converged);
  const int n = int(exact.coupling.rows());
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      EXPECT_LT(std::fabs(exact.coupling(a, b) - stratified.coupling(a, b)),
                5.0 * stratified.couplingError(a, b) + 1e-12)
          << "K[" << a << "][" << b << "] degree " << degree;
    }
  }
}

TEST(ExactGold, AgreesWithTheDenseStratifiedGoldOnOccludedLinks) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  {  // two overlapping tilted blockers: their shadows need a polygon union
    OccluderScene scene;
    addTwoTiltedBlockers(scene);
    scene.commit();
    const Link link{receiver, source, &scene};
    expectAgreesWithDenseGold(link, 0);
    expectAgreesWithDenseGold(link, 2);
  }
  {  // an occluder crossing the receiver's plane, and one touching the source
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.4, -0.3, -0.3}, {0, 0.9, 0}, {0.1, 0, 0.7}, "crossing"));
    scene.addParallelogram(Patch::make({0.6, 0.2, 1.0}, {0, 0.5, 0}, {0, 0, -0.4}, "touching"));
    scene.commit();
    expectAgreesWithDenseGold(Link{receiver, source, &scene}, 1);
  }
}

TEST(ExactGold, ATriangleSoupIsCulledToItsShaftAndAgreesWithTheDenseGold) {
  // 1,000 small triangles, most of them away from the link: the shaft cull keeps few.
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t t = 0; t < 1000; ++t) {
    const Eigen::Vector3d centre(6 * uniform(random) - 2.5, 6 * uniform(random) - 2.5,
                                 0.2 + 0.6 * uniform(random));
    for (int c = 0; c < 3; ++c) {
      vertices.push_back(centre + 0.08 * Eigen::Vector3d(uniform(random) - 0.5,
                                                         uniform(random) - 0.5,
                                                         uniform(random) - 0.5));
    }
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  OccluderScene scene;
  scene.addTriangleMesh(vertices, triangles);
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const Link link{receiver, source, &scene};
  const ExactVisibility visibility(link);
  EXPECT_LT(visibility.candidateCount(), 100u);
  EXPECT_GT(visibility.candidateCount(), 5u);
  expectAgreesWithDenseGold(link, 0);
}

TEST(ExactGold, TheErrorEstimateBoundsTheTrueError) {
  // Over varied occluded links, the error reported at a loose tolerance exceeds the
  // difference from a run 1,000 times tighter, for every coefficient.
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  int checked = 0;
  for (int k = 0; k < 12; ++k) {
    const double height = 0.5 + 1.5 * uniform(random);
    const Patch source = Patch::make({uniform(random) - 0.5, 1.0 + uniform(random), height},
                                     {1.0, 0.0, 0.3 * uniform(random)},
                                     {0.2 * uniform(random), -1.0, 0.0}, "source");
    OccluderScene scene;
    for (int b = 0; b < 1 + k % 3; ++b) {
      scene.addParallelogram(Patch::make(
          {uniform(random) - 0.3, uniform(random) - 0.3, height * (0.2 + 0.6 * uniform(random))},
          {0.2 + 0.4 * uniform(random), 0.1 * uniform(random), 0.1 * uniform(random)},
          {0.1 * uniform(random), 0.2 + 0.4 * uniform(random), 0.0}, "blocker"));
    }
    scene.commit();
    const Link link{receiver, source, &scene};
    const int degree = k % 2;
    ExactGoldOptions loose, tight;
    loose.tolerance = 1e-4;
    tight.tolerance = 1e-7;
    const ExactGold estimate = exactGold(link, degree, loose);
    const ExactGold truth = exactGold(link, degree, tight);
    if (truth.coupling(0, 0) <= 0.0) continue;
    ++checked;
    const Eigen::MatrixXd error = (estimate.coupling - truth.coupling).cwiseAbs();
    for (int a = 0; a < error.rows(); ++a) {
      for (int b = 0; b < error.cols(); ++b) {
        EXPECT_LE(error(a, b), estimate.couplingError(a, b) + truth.couplingError(a, b))
            << "link " << k << " K[" << a << "][" << b << "]";
      }
    }
  }
  EXPECT_GE(checked, 10);
}

// Two integrations of one K, with different integrands on the receiver: S' minus the
// shadows at every point, or S' apart (Gauss products of rising order) and the shadows
// alone (the default at degree >= 1). Each must fall within the other's error.
void expectApartAgreesWithTogether(const Link& link, int degree, double tolerance) {
  ExactGoldOptions apart, together;
  apart.tolerance = together.tolerance = tolerance;
  together.unoccludedApart = false;
  const ExactGold a = exactGold(link, degree, apart), b = exactGold(link, degree, together);
  EXPECT_TRUE(a.unoccludedApart);
  EXPECT_FALSE(b.unoccludedApart);
  EXPECT_TRUE(a.converged);
  EXPECT_TRUE(b.converged);
  const double largest = b.coupling.cwiseAbs().maxCoeff();
  EXPECT_LE(a.couplingError.maxCoeff(), tolerance * largest * (1 + 1e-9));
  expectWithinSummedErrors(a, b, "degree " + std::to_string(degree));
}

TEST(ExactGold, TheUnoccludedPartApartAgreesWithTheWholeIntegral) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  {  // two overlapping tilted blockers
    OccluderScene scene;
    addTwoTiltedBlockers(scene);
    scene.commit();
    for (const int degree : {1, 2}) expectApartAgreesWithTogether({receiver, source, &scene}, degree, 1e-6);
  }
  {  // a blocker hiding all but a sliver (x_r + x_s > 1.99): K's largest entry is about 1e-4
     // of its unoccluded part's, whose error must then be held far below its own tolerance
     // (higher Gauss orders after the shadows' part)
    OccluderScene scene;
    scene.addParallelogram(Patch::make({-0.5, -0.5, 0.5}, {1.499, 0, 0}, {0, 2.0, 0}, "blocker"));
    scene.commit();
    const Link link{receiver, source, &scene};
    expectApartAgreesWithTogether(link, 2, 1e-5);
    const ExactGold gold = exactGold(link, 0);
    EXPECT_LT(gold.formFactor, 0.1 * analytic::parallelRectangles(1, 1, 1));
    EXPECT_FALSE(gold.unoccludedApart);  // degree 0: Lambert's formula costs S' four edges
  }
  {  // a receiver crossing the source's plane: S' is not the same from every point
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.2, 0.2, 0.5}, {0.4, 0, 0}, {0, 0.4, 0}, "blocker"));
    scene.commit();
    const Patch tilted = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 0.5, 1.5}, "tilted");
    ExactGoldOptions options;
    options.tolerance = 1e-5;
    const ExactGold gold = exactGold({tilted, source, &scene}, 1, options);
    EXPECT_FALSE(gold.unoccludedApart);
    EXPECT_TRUE(gold.converged);
  }
}

TEST(ExactGold, AGrazingLinkKeepsItsErrorEstimate) {
  // A receiver beside the source and a twentieth of its size above its plane sees it at
  // grazing angles: its points' inner integrals are small sums of large terms that cancel.
  // At the study's tolerance the gold, with its unoccluded part apart or not, must stay within
  // its estimate of a run at 1e-8 (tight inner rules, the whole integral at once). With the
  // loose inner rules in the unoccluded part its actual error reached 6, 100 and 174 times
  // its estimate (degrees 1-3), and 3 times at degree 3 with the loose rules everywhere.
  const Patch source = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "source");
  const Patch receiver = Patch::make({1.3, 1, 0.05}, {0, -1, 0}, {1, 0, 0.05}, "receiver");
  OccluderScene scene;
  scene.addParallelogram(Patch::make({1.1, 0.2, 0.0005}, {0, 0.3, 0}, {0, 0, 0.01}, "blocker"));
  scene.commit();
  const Link link{receiver, source, &scene};
  for (const int degree : {1, 2, 3}) {
    ExactGoldOptions tight;
    tight.tolerance = 1e-8;
    tight.unoccludedApart = false;
    const ExactGold truth = exactGold(link, degree, tight);
    ASSERT_TRUE(truth.converged);
    for (const bool apart : {true, false}) {
      ExactGoldOptions study;
      study.tolerance = 3e-4;
      study.unoccludedApart = apart;
      const ExactGold gold = exactGold(link, degree, study);
      EXPECT_EQ(gold.unoccludedApart, apart);
      EXPECT_TRUE(gold.converged);
      expectWithinSummedErrors(gold, truth, "degree " + std::to_string(degree) + " apart " +
                                                std::to_string(apart));
    }
  }
}

TEST(ExactGold, IsDeterministic) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.1, 0.1, 0.4}, {0.5, 0.1, 0.05}, {0.05, 0.5, 0}, "a"));
  scene.commit();
  const Link link{Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver"),
                  Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source"), &scene};
  const ExactGold first = exactGold(link, 1), second = exactGold(link, 1);
  EXPECT_EQ(first.coupling, second.coupling);
  EXPECT_EQ(first.couplingError, second.couplingError);
}

}  // namespace
}  // namespace radquad
