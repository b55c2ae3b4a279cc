// Gathering through a product rule's source points (radiosity/source_projection.h): the
// aliasing matrices against closed forms, and K B against the kept columns times the
// projection, on couplings integrated with every source rule up to d+1 points per axis; the
// truncated gather against the truncated source, and against the aliased one where the
// kernel is smooth.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "kernel/legendre_basis.h"
#include "kernel/occluder_scene.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/source_projection.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

TEST(SourceProjectionTest, AliasingIsTheIdentityOnTheRulesOwnOrders) {
  // sum_i w_i phi_p phi_p' is exact for p + p' <= 2S - 1, so orthonormality gives delta.
  for (int degree = 0; degree <= 4; ++degree) {
    const SourceProjection projection(degree, DroppedOrders::kAliased);
    for (int points = 1; points <= degree + 1; ++points) {
      for (int p = 0; p < points; ++p) {
        for (int q = 0; q < points; ++q) {
          EXPECT_NEAR(projection.matrix(points, p, q), p == q ? 1.0 : 0.0, 1e-14)
              << degree << " " << points << " " << p << " " << q;
        }
      }
    }
  }
}

TEST(SourceProjectionTest, OnePointAliasesEveryOrderOntoItsValueAtTheMidpoint) {
  // One Gauss point: x = 1/2, w = 1, so M_1[0][p'] = phi_p'(1/2) = sqrt(2p'+1) P_p'(0):
  // 1, 0, -sqrt(5)/2, 0 for p' = 0..3.
  const SourceProjection projection(3, DroppedOrders::kAliased);
  EXPECT_NEAR(projection.matrix(1, 0, 0), 1.0, 1e-15);
  EXPECT_NEAR(projection.matrix(1, 0, 1), 0.0, 1e-15);
  EXPECT_NEAR(projection.matrix(1, 0, 2), -std::sqrt(5.0) / 2.0, 1e-15);
  EXPECT_NEAR(projection.matrix(1, 0, 3), 0.0, 1e-15);
  // Two points, order 2 onto order 0: sum_i w_i phi_2(x_i) = 0 (the rule integrates phi_2
  // exactly) and onto order 1: sum_i w_i phi_1 phi_2 = 0 (degree 3 <= 2*2 - 1): no aliasing
  // below order 2; order 3 onto order 1 is not exact (degree 4).
  EXPECT_NEAR(projection.matrix(2, 0, 2), 0.0, 1e-15);
  EXPECT_NEAR(projection.matrix(2, 1, 2), 0.0, 1e-15);
  // phi_1 phi_3 at x = 1/2 -+ 1/(2 sqrt 3): t = 2x - 1 = -+1/sqrt3, P_1 P_3 summed with
  // weights 1/2: (1/sqrt3)(P_3(1/sqrt3)) with P_3(t) = (5t^3 - 3t)/2 = -2/(3 sqrt3), so
  // sqrt3 sqrt7 (1/sqrt3)(-2/(3 sqrt3)) = -2 sqrt7 / (3 sqrt3).
  EXPECT_NEAR(projection.matrix(2, 1, 3), -2.0 * std::sqrt(7.0) / (3.0 * std::sqrt(3.0)),
              1e-14);
}

// K B against the kept columns times the projection, for every source rule, on an
// unoccluded and a partially occluded link.
TEST(SourceProjectionTest, KeptColumnsTimesProjectionEqualTheFullGather) {
  OccluderScene blocker;
  blocker.addParallelogram(
      Patch::make(Vec(0.2, 0.3, 0.6), Vec(0.5, 0, 0), Vec(0, 0.3, 0), "blocker"));
  blocker.commit();
  const Patch source = Patch::make(Vec::Zero(), Vec(1.2, 0, 0), Vec(0.1, 0.9, 0), "source");
  const Patch receiver =
      Patch::make(Vec(0.1, -0.2, 1.3), Vec(0, 1.1, 0.2), Vec(0.8, 0, -0.1), "receiver");
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  for (int degree = 1; degree <= 3; ++degree) {
    const int n = degree + 1, functions = n * n;
    const GaussTables tables(degree);
    const SourceProjection projection(degree, DroppedOrders::kAliased);
    Eigen::MatrixXd radiosity(functions, 3);
    for (int k = 0; k < functions * 3; ++k) radiosity.data()[k] = coefficient(random);
    const std::array<const OccluderScene*, 2> visibility = {nullptr, &blocker};
    for (const OccluderScene* occluders : visibility) {
      const Link link{receiver, source, occluders};
      for (int pu = 1; pu <= n; ++pu) {
        for (int pv = 1; pv <= n; ++pv) {
          const GaussSide& r = tables.side(n, n);
          const GaussSide& s = tables.side(pu, pv);
          CouplingAccumulator accumulator;
          LinkIntegral integral;
          accumulator.product(link, r.samples, r.basis, s.samples, s.basis, integral);
          if (occluders) {  // partially occluded: some rays blocked, not all
            EXPECT_GT(integral.raysBlocked, 0u);
            EXPECT_LT(integral.raysBlocked, integral.raysCast);
          }
          const Eigen::MatrixXd full = integral.coupling * radiosity;
          Eigen::MatrixXd kept = integral.coupling;
          projection.compact(pu, pv, kept.data());
          // The kept columns are the original (p, q) columns, p < pu, q < pv.
          for (int p = 0; p < pu; ++p) {
            for (int q = 0; q < pv; ++q) {
              EXPECT_EQ(kept.col(p * pv + q), integral.coupling.col(p * n + q));
            }
          }
          Eigen::MatrixXd projected(pu * pv, 3);
          projection.project(pu, pv, radiosity.data(), projected.data());
          const Eigen::MatrixXd factored = kept.leftCols(pu * pv) * projected;
          EXPECT_LE((factored - full).norm(), 1e-13 * full.norm())
              << "degree " << degree << " points " << pu << "x" << pv
              << (occluders ? " occluded" : " open");
        }
      }
    }
  }
}

TEST(SourceProjectionTest, FewerPointsThanOrdersAliasHigherOrders) {
  // The projection is not the truncation: with pu < d+1 a higher-order coefficient moves
  // onto the low orders (a quadratic along u seen by one point is its midpoint value).
  const SourceProjection projection(2, DroppedOrders::kAliased);
  Eigen::MatrixXd radiosity = Eigen::MatrixXd::Zero(9, 3);
  radiosity(2 * 3 + 0, 0) = 1.0;  // phi_2(u) phi_0(v), channel 0
  Eigen::MatrixXd projected(1 * 3, 3);
  projection.project(1, 3, radiosity.data(), projected.data());
  EXPECT_NEAR(projected(0, 0), -std::sqrt(5.0) / 2.0, 1e-15);  // phi_2(1/2) onto (0, 0)
  EXPECT_NEAR(projected(1, 0), 0.0, 1e-15);
  EXPECT_NEAR(projected(2, 0), 0.0, 1e-15);
  EXPECT_EQ(projected.col(1).norm(), 0.0);
}

TEST(SourceProjectionTest, TruncatedGatherIsTheKeptColumnsTimesTheTruncatedSource) {
  const Patch source = Patch::make(Vec::Zero(), Vec(1.2, 0, 0), Vec(0.1, 0.9, 0), "source");
  const Patch receiver =
      Patch::make(Vec(0.1, -0.2, 1.3), Vec(0, 1.1, 0.2), Vec(0.8, 0, -0.1), "receiver");
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  for (int degree = 1; degree <= 3; ++degree) {
    const int n = degree + 1, functions = n * n;
    const GaussTables tables(degree);
    const SourceProjection projection(degree, DroppedOrders::kTruncated);
    Eigen::MatrixXd radiosity(functions, 3);
    for (int k = 0; k < functions * 3; ++k) radiosity.data()[k] = coefficient(random);
    const Link link{receiver, source, nullptr};
    for (int pu = 1; pu <= n; ++pu) {
      for (int pv = 1; pv <= n; ++pv) {
        for (int p = 0; p < pu; ++p) {
          for (int q = 0; q < n; ++q) {
            EXPECT_EQ(projection.matrix(pu, p, q), p == q ? 1.0 : 0.0);
          }
        }
        const GaussSide& r = tables.side(n, n);
        const GaussSide& s = tables.side(pu, pv);
        CouplingAccumulator accumulator;
        LinkIntegral integral;
        accumulator.product(link, r.samples, r.basis, s.samples, s.basis, integral);
        // The source with its orders (p, q), p >= pu or q >= pv, set to 0.
        Eigen::MatrixXd truncated = radiosity;
        for (int p = 0; p < n; ++p) {
          for (int q = 0; q < n; ++q) {
            if (p >= pu || q >= pv) truncated.row(p * n + q).setZero();
          }
        }
        const Eigen::MatrixXd expected = integral.coupling * truncated;
        Eigen::MatrixXd kept = integral.coupling;
        projection.compact(pu, pv, kept.data());
        Eigen::MatrixXd projected(pu * pv, 3);
        projection.project(pu, pv, radiosity.data(), projected.data());
        const Eigen::MatrixXd factored = kept.leftCols(pu * pv) * projected;
        EXPECT_LE((factored - expected).norm(), 1e-13 * expected.norm())
            << "degree " << degree << " points " << pu << "x" << pv;
      }
    }
  }
}

// A far, smooth link and a source that is a pure quadratic along u: the exact gather,
// int G phi_2, is nearly 0 (phi_2 is orthogonal to the linear part of G). One point along u
// sees phi_2 at its midpoint, -sqrt(5)/2: aliased, that value is gathered as if it were the
// mean; truncated, the order is dropped, and the error is the small exact gather itself.
TEST(SourceProjectionTest, TruncationIsCloserThanAliasingOnASmoothKernel) {
  const Patch source = Patch::make(Vec::Zero(), Vec(1, 0, 0), Vec(0, 1, 0), "source");
  const Patch receiver =
      Patch::make(Vec(0.5, 3.0, 2.5), Vec(1, 0, 0), Vec(0, 0.6, 0.8), "receiver");
  const int degree = 2, n = 3;
  const GaussTables tables(degree);
  Eigen::MatrixXd radiosity = Eigen::MatrixXd::Zero(9, 3);
  radiosity.row(0).setConstant(1.0);        // mean 1
  radiosity.row(2 * n + 0).setConstant(0.3);  // phi_2(u) phi_0(v)
  const Link link{receiver, source, nullptr};
  CouplingAccumulator accumulator;
  LinkIntegral exact, reduced;
  accumulator.product(link, tables.side(n, n).samples, tables.side(n, n).basis,
                      tables.side(n, n).samples, tables.side(n, n).basis, exact);
  accumulator.product(link, tables.side(n, n).samples, tables.side(n, n).basis,
                      tables.side(1, n).samples, tables.side(1, n).basis, reduced);
  const Eigen::MatrixXd reference = exact.coupling * radiosity;
  double errors[2];
  for (DroppedOrders dropped : {DroppedOrders::kTruncated, DroppedOrders::kAliased}) {
    const SourceProjection projection(degree, dropped);
    Eigen::MatrixXd kept = reduced.coupling;
    projection.compact(1, n, kept.data());
    Eigen::MatrixXd projected(n, 3);
    projection.project(1, n, radiosity.data(), projected.data());
    errors[dropped == DroppedOrders::kTruncated ? 0 : 1] =
        (kept.leftCols(n) * projected - reference).norm() / reference.norm();
  }
  // Aliased: about 0.3 sqrt(5)/2 = 34% of the mean's gather; truncated: the kernel's own
  // variation, a few percent.
  EXPECT_GT(errors[1], 0.25);
  EXPECT_LT(errors[0], 0.1 * errors[1]);
}

}  // namespace
}  // namespace radquad
