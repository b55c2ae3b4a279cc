#include "radiosity/source_projection.h"
#include "kernel/input_error.h"

#include <cstring>

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {

const char* droppedOrdersName(DroppedOrders orders) {
  return orders == DroppedOrders::kTruncated ? "truncated" : "aliased";
}

SourceProjection::SourceProjection(int degree, DroppedOrders dropped)
    : degree_(degree), dropped_(dropped) {
  validateBasisDegree(degree);
  const int orders = degree + 1;
  matrices_.resize(std::size_t(orders));
  double phi[kMaxBasisDegree + 1];
  for (int points = 1; points <= orders; ++points) {
    std::vector<double>& m = matrices_[std::size_t(points - 1)];
    m.assign(std::size_t(points * orders), 0.0);
    if (dropped == DroppedOrders::kTruncated) {
      for (int p = 0; p < points; ++p) m[std::size_t(p * orders + p)] = 1.0;
      continue;
    }
    const GaussLegendreRule& rule = gaussLegendreUnit(points);
    for (int i = 0; i < points; ++i) {
      shiftedLegendreValues(degree, rule.nodes[std::size_t(i)], phi);
      for (int p = 0; p < points; ++p) {
        for (int q = 0; q < orders; ++q) {
          m[std::size_t(p * orders + q)] += rule.weights[std::size_t(i)] * phi[p] * phi[q];
        }
      }
    }
  }
}

double SourceProjection::matrix(int points, int p, int pPrime) const {
  RADQUAD_REQUIRE(points >= 1 && points <= degree_ + 1 && p < points && pPrime <= degree_);
  return matrices_[std::size_t(points - 1)][std::size_t(p * (degree_ + 1) + pPrime)];
}

void SourceProjection::project(int pointsU, int pointsV, const double* radiosity,
                               double* out) const {
  const int orders = degree_ + 1;
  const std::size_t functions = std::size_t(orders * orders);
  const std::size_t rows = std::size_t(pointsU * pointsV);
  RADQUAD_REQUIRE(pointsU >= 1 && pointsU <= orders && pointsV >= 1 && pointsV <= orders);
  const double* mu = matrices_[std::size_t(pointsU - 1)].data();
  const double* mv = matrices_[std::size_t(pointsV - 1)].data();
  for (int c = 0; c < 3; ++c) {
    const double* b = radiosity + std::size_t(c) * functions;
    // Along u first: t[p][j] = sum_i M_u[p][i] B[i][j], then along v.
    double t[(kMaxBasisDegree + 1) * (kMaxBasisDegree + 1)];
    for (int p = 0; p < pointsU; ++p) {
      for (int j = 0; j < orders; ++j) {
        double sum = 0.0;
        for (int i = 0; i < orders; ++i) sum += mu[p * orders + i] * b[i * orders + j];
        t[p * orders + j] = sum;
      }
    }
    double* target = out + std::size_t(c) * rows;
    for (int p = 0; p < pointsU; ++p) {
      for (int q = 0; q < pointsV; ++q) {
        double sum = 0.0;
        for (int j = 0; j < orders; ++j) sum += mv[q * orders + j] * t[p * orders + j];
        target[p * pointsV + q] = sum;
      }
    }
  }
}

void SourceProjection::compact(int pointsU, int pointsV, double* coupling) const {
  const int orders = degree_ + 1;
  const std::size_t functions = std::size_t(orders * orders);
  // Column (p, q) moves from p * orders + q to p * pointsV + q <= it, in increasing order,
  // so no column is overwritten before it is moved.
  for (int p = 0; p < pointsU; ++p) {
    for (int q = 0; q < pointsV; ++q) {
      const std::size_t from = std::size_t(p * orders + q), to = std::size_t(p * pointsV + q);
      if (from != to) {
        std::memcpy(coupling + to * functions, coupling + from * functions,
                    functions * sizeof(double));
      }
    }
  }
}

}  // namespace radquad
