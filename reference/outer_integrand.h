// The exact gold's integrand over the receiver's unit square (exact_gold.h): at (s, t), the
// basis functions at the receiver point times the inner integrals over what it sees of the
// source (exact_visibility.h, source_moments.h), and the batches, Gauss products and sizes the
// outer integrations share. Internal to the exact gold (exact_gold.cpp,
// critical_line_cubature.h).
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "kernel/coupling.h"
#include "kernel/legendre_basis.h"
#include "kernel/progress_throttle.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"

namespace radquad::exact_gold_detail {

// One thread's scratch: visibility and inner integrals are computed per point.
struct Worker {
  ExactVisibility visibility;
  SourceMoments moments;
  VisibleRings rings;
  std::vector<double> inner;
  std::vector<double> receiverValues;
  std::vector<double> samples;  // scratch of the critical-line cubature
  bool finite = true;

  Worker(const Link& link, int degree, double innerAccuracy)
      : visibility(link),
        moments(link.source, degree, innerAccuracy),
        inner(std::size_t(basisFunctionCount(degree))),
        receiverValues(std::size_t(basisFunctionCount(degree))) {}
};

struct OuterIntegrand {
  const Link& link;
  int degree;
  int functions;
  double scale;  // sqrt(A_r / A_s)
  tbb::enumerable_thread_specific<Worker> workers;
  std::uint64_t points = 0;
  // Integrate minus the shadows' union alone, leaving out S' (the source in front of the
  // receiver's plane, the same polygon from every receiver point): the unoccluded part apart.
  bool shadowsOnly = false;
  // Progress (ExactGoldOptions::progress), from the calling thread.
  std::function<void(std::uint64_t, double)> progress;
  ProgressThrottle throttle;

  void report(std::uint64_t pointsSoFar) {
    if (!progress) return;
    if (const auto now = throttle.due()) progress(pointsSoFar, *now);
  }

  // The inner integrals to a hundredth of the outer tolerance (source_moments.h).
  OuterIntegrand(const Link& l, int d, double tolerance)
      : link(l),
        degree(d),
        functions(basisFunctionCount(d)),
        scale(std::sqrt(l.receiver.area / l.source.area)),
        workers([&l, d, tolerance] { return Worker(l, d, 1e-2 * tolerance); }) {}

  // The point's functions^2 values into `out`; its inner integrals (functions values) into
  // `inner` too unless it is null.
  void evaluate(Worker& worker, double s, double t, double* out, double* inner = nullptr) const {
    const Eigen::Vector3d x = link.receiver.pointAt(s, t);
    worker.visibility.visibleRings(x, worker.rings);
    if (shadowsOnly) worker.rings.dropFirst();
    worker.moments.compute(x, link.receiver.normal, worker.rings, worker.inner.data());
    expand(worker.receiverValues.data(), s, t, worker.inner.data(), out);
    for (int b = 0; b < functions; ++b) worker.finite = worker.finite && std::isfinite(worker.inner[b]);
    if (inner) std::copy(worker.inner.begin(), worker.inner.end(), inner);
  }

  // The values at (s, t) from its inner integrals; receiverValues: scratch of `functions`.
  void expand(double* receiverValues, double s, double t, const double* inner, double* out) const {
    tensorBasisValues(degree, s, t, receiverValues);
    for (int a = 0; a < functions; ++a) {
      const double weight = scale * receiverValues[a];
      for (int b = 0; b < functions; ++b) out[a * functions + b] = weight * inner[b];
    }
  }

  bool finite() {
    bool all = true;
    for (const Worker& worker : workers) all = all && worker.finite;
    return all;
  }
};


// Genz-Malik's batch (genz_malik.h): the points are independent, so a batch is spread over
// threads, and the values do not depend on which thread computed them.
void evaluateBatch(OuterIntegrand& integrand, std::size_t count, const double* points, double* out);

// The n x n Gauss-Legendre product over the receiver's square of the integrand's values,
// summed in a fixed order (the points spread over threads by evaluateBatch).
std::vector<double> gaussProduct(OuterIntegrand& integrand, int n);

// max_v |known[v] + value[v]| (known empty: max |value|): the size of a whole integral whose
// part `known` was integrated apart.
double largestOfSum(const std::vector<double>& known, const std::vector<double>& value);

}  // namespace radquad::exact_gold_detail
