// The exact gold's Genz-Malik cubature: its rule's exactness degrees, its adaptive runs
// against libcubature's hcubature (an independent implementation of the same rule and
// bisection), its starting grid and its budget.
#include <gtest/gtest.h>

#include <cubature.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "kernel/input_error.h"
#include "reference/genz_malik.h"

namespace radquad {
namespace {

using Scalar = std::function<double(double, double)>;

BatchIntegrand batchOf(const Scalar& f) {
  return [f](std::size_t count, const double* points, double* out) {
    for (std::size_t k = 0; k < count; ++k) out[k] = f(points[2 * k], points[2 * k + 1]);
  };
}

// A tolerance no run can miss: the initial grid's rules alone.
GenzMalikResult rulesOnly(const Scalar& f, int grid) {
  GenzMalikOptions options;
  options.tolerance = 1e300;
  options.initialGrid = grid;
  return genzMalik2d(1, batchOf(f), options);
}

TEST(GenzMalik, TheRuleIsExactToDegreeSevenAndItsEstimateVanishesToDegreeFive) {
  for (int grid : {1, 3}) {
    for (int a = 0; a <= 8; ++a) {
      for (int b = 0; a + b <= 8; ++b) {
        const GenzMalikResult run =
            rulesOnly([a, b](double s, double t) { return std::pow(s, a) * std::pow(t, b); }, grid);
        ASSERT_EQ(run.points, std::uint64_t(grid * grid * kGenzMalikPoints));
        const double exact = 1.0 / ((a + 1) * (b + 1));
        if (a + b <= 7) {
          EXPECT_NEAR(run.value[0], exact, 1e-15) << "s^" << a << " t^" << b << " grid " << grid;
        }
        if (a + b <= 5) {
          EXPECT_LT(run.error[0], 1e-15) << "s^" << a << " t^" << b << " grid " << grid;
        }
      }
    }
    // Beyond: the degree-8 monomials in one variable are not integrated exactly, and the
    // embedded rule sees degree 6.
    const GenzMalikResult eighth = rulesOnly([](double s, double) { return std::pow(s, 8); }, grid);
    EXPECT_GT(std::abs(eighth.value[0] - 1.0 / 9.0), 1e-11);
    const GenzMalikResult sixth = rulesOnly([](double, double t) { return std::pow(t, 6); }, grid);
    EXPECT_GT(sixth.error[0], 1e-9);
  }
}

struct Reference {
  double value = 0.0, error = 0.0;
  std::size_t points = 0;
};

// hcubature's serial run (one region halved at a time) on [0,1]^2.
Reference hcubatureRun(const Scalar& f, double tolerance) {
  struct Data {
    const Scalar* f;
    std::size_t points = 0;
  } data{&f};
  auto callback = [](unsigned, const double* x, void* raw, unsigned, double* out) -> int {
    auto& d = *static_cast<Data*>(raw);
    ++d.points;
    out[0] = (*d.f)(x[0], x[1]);
    return 0;
  };
  const double low[2] = {0.0, 0.0}, high[2] = {1.0, 1.0};
  Reference reference;
  EXPECT_EQ(hcubature(1, callback, &data, 2, low, high, 0, 0.0, tolerance, ERROR_INDIVIDUAL,
                      &reference.value, &reference.error),
            0);
  reference.points = data.points;
  return reference;
}

TEST(GenzMalik, HalvingOneRegionAtATimeRetracesHcubature) {
  // Smooth, peaked and kinked integrands, none symmetric in s and t and none a polynomial
  // of degree 3 or less in both on any region, so no axis choice falls on a tie (there
  // hcubature takes s, and ours the wider axis).
  const std::vector<std::pair<const char*, Scalar>> integrands = {
      {"exponential", [](double s, double t) { return std::exp(1.3 * s - 0.7 * t * t); }},
      {"peak", [](double s, double t) {
         return 1.0 / (0.01 + (s - 0.3) * (s - 0.3) + 2.0 * (t - 0.6) * (t - 0.6));
       }},
      {"kink", [](double s, double t) { return std::abs(s + 0.37 * t - 0.55) * std::exp(t); }},
  };
  for (const auto& [name, f] : integrands) {
    for (double tolerance : {1e-3, 1e-6}) {
      GenzMalikOptions options;
      options.tolerance = tolerance;
      options.batchRegions = 1;
      const GenzMalikResult ours = genzMalik2d(1, batchOf(f), options);
      const Reference theirs = hcubatureRun(f, tolerance);
      EXPECT_TRUE(ours.converged) << name;
      if (name == std::string("kink") && tolerance < 1e-4) {
        // Deep in the kink's refinement many regions have equal errors, and the two heaps
        // take them in different orders: the runs stop a few regions apart.
        EXPECT_NEAR(double(ours.points), double(theirs.points), 0.02 * double(theirs.points));
        EXPECT_LE(std::abs(ours.value[0] - theirs.value), ours.error[0] + theirs.error);
        continue;
      }
      EXPECT_EQ(ours.points, theirs.points) << name << " at " << tolerance;
      EXPECT_NEAR(ours.value[0], theirs.value, 1e-12 * std::abs(theirs.value)) << name;
      EXPECT_NEAR(ours.error[0], theirs.error, 1e-9 * theirs.error) << name;
    }
  }
}

TEST(GenzMalik, BatchedRunsMeetTheToleranceOnEveryComponent) {
  // Two components of different sizes: the tolerance is relative to the larger, and the
  // true error of each stays below the estimate.
  const BatchIntegrand f = [](std::size_t count, const double* points, double* out) {
    for (std::size_t k = 0; k < count; ++k) {
      const double s = points[2 * k], t = points[2 * k + 1];
      out[2 * k] = std::exp(s + t);
      out[2 * k + 1] = 1e-3 * std::sqrt(s * s + t * t);
    }
  };
  const double exact[2] = {(std::exp(1.0) - 1.0) * (std::exp(1.0) - 1.0),
                           1e-3 * (std::sqrt(2.0) + std::log(1.0 + std::sqrt(2.0))) / 3.0};
  for (int grid : {1, 4}) {
    GenzMalikOptions options;
    options.tolerance = 1e-9;
    options.initialGrid = grid;
    const GenzMalikResult run = genzMalik2d(2, f, options);
    ASSERT_TRUE(run.converged);
    for (int v = 0; v < 2; ++v) {
      EXPECT_LE(run.error[v], 1e-9 * run.value[0]);
      EXPECT_LE(std::abs(run.value[v] - exact[v]), run.error[v] + 1e-15) << v;
    }
  }
}

TEST(GenzMalik, AFeatureBetweenTheFirstRegionsPointsNeedsTheGrid) {
  // A narrow bump away from every point of the single region's rule: the lone region is
  // blind to it and stops at once; a grid of 8 x 8 regions sees it and integrates it.
  const Scalar bump = [](double s, double t) {
    const double r2 = (s - 0.25) * (s - 0.25) + (t - 0.75) * (t - 0.75);
    return 1.0 + 50.0 * std::exp(-r2 / (2 * 0.02 * 0.02));
  };
  const double exact = 1.0 + 50.0 * 2.0 * M_PI * 0.02 * 0.02;  // the bump lies well inside
  GenzMalikOptions options;
  options.tolerance = 1e-4;
  const GenzMalikResult lone = genzMalik2d(1, batchOf(bump), options);
  EXPECT_EQ(lone.points, std::uint64_t(kGenzMalikPoints));
  EXPECT_GT(std::abs(lone.value[0] - exact), 100 * lone.error[0]);
  options.initialGrid = 8;
  const GenzMalikResult grid = genzMalik2d(1, batchOf(bump), options);
  EXPECT_TRUE(grid.converged);
  EXPECT_LE(std::abs(grid.value[0] - exact), grid.error[0]);
}

TEST(GenzMalik, ABaselineSetsTheSizeTheToleranceIsRelativeTo) {
  // The rest of an integral whose known part is 1: the run stops when its error is 1e-6 of
  // |1 + its value|, far sooner than at 1e-6 of its own small value, and is still within
  // its estimate of the closed form; without the baseline it meets the tighter target.
  const Scalar small = [](double s, double t) { return 1e-3 * std::exp(3.0 * (s + t)); };
  const double exact = 1e-3 * std::pow((std::exp(3.0) - 1.0) / 3.0, 2);
  GenzMalikOptions alone;
  alone.tolerance = 1e-6;
  GenzMalikOptions rest = alone;
  rest.baseline = {1.0};
  const GenzMalikResult own = genzMalik2d(1, batchOf(small), alone);
  const GenzMalikResult part = genzMalik2d(1, batchOf(small), rest);
  ASSERT_TRUE(own.converged);
  ASSERT_TRUE(part.converged);
  EXPECT_LE(own.error[0], 1e-6 * own.value[0]);
  EXPECT_LE(part.error[0], 1e-6 * (1.0 + part.value[0]));
  EXPECT_GT(part.error[0], 1e-6 * part.value[0]);  // the run took the looser target
  EXPECT_LT(part.points, own.points);
  for (const GenzMalikResult* run : {&own, &part}) {
    EXPECT_LE(std::abs(run->value[0] - exact), run->error[0]);
  }
  rest.baseline = {1.0, 2.0};  // one value per integrand
  EXPECT_THROW(genzMalik2d(1, batchOf(small), rest), InputError);
}

TEST(GenzMalik, StopsUnconvergedAtItsBudgetAndRejectsBadOptions) {
  const Scalar singular = [](double s, double t) { return 1.0 / std::sqrt(s * s + t * t + 1e-300); };
  GenzMalikOptions options;
  options.tolerance = 1e-14;
  options.maxEvaluations = 2000;
  const GenzMalikResult run = genzMalik2d(1, batchOf(singular), options);
  EXPECT_FALSE(run.converged);
  EXPECT_LE(run.points, 2000u);
  EXPECT_GT(run.points, 2000u - 2 * kGenzMalikPoints);
  GenzMalikOptions bad;
  bad.initialGrid = 0;
  EXPECT_THROW(genzMalik2d(1, batchOf(singular), bad), InputError);
  bad = {};
  bad.tolerance = 0.0;
  EXPECT_THROW(genzMalik2d(1, batchOf(singular), bad), InputError);
  bad = {};
  bad.initialGrid = 20;
  bad.maxEvaluations = 1000;
  EXPECT_THROW(genzMalik2d(1, batchOf(singular), bad), InputError);
}

}  // namespace
}  // namespace radquad
