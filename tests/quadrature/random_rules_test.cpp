// The random rules: their stratification, their reproducibility and their unbiasedness.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "quadrature/prepared_rule.h"
#include "quadrature/random/philox.h"
#include "quadrature/random/random_rule.h"
#include "quadrature/random/seeds.h"
#include "quadrature/registry.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

// Unit squares facing each other at distance 1 (receiver at z = 0 facing +z).
Link parallelSquares() {
  return Link{Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver"),
              Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source"), nullptr};
}

TEST(NRook, EveryStratumOfEveryAxisHoldsExactlyOnePoint) {
  for (const std::string name : {"NRook", "NRook:1000", "NRook:1"}) {
    const auto rule = findRule(name);
    const std::size_t n = rule->sampleCount();
    for (std::uint64_t seed : {0ull, 1ull, 987654321ull}) {
      const LinkSamples p = rule->samples(seed).points;
      ASSERT_EQ(p.size(), n);
      for (const std::vector<double>* axis : {&p.s, &p.t, &p.u, &p.v}) {
        std::vector<int> hits(n, 0);
        for (double x : *axis) {
          ASSERT_GE(x, 0.0);
          ASSERT_LT(x, 1.0);
          ++hits[std::size_t(x * double(n))];
        }
        for (std::size_t stratum = 0; stratum < n; ++stratum) {
          ASSERT_EQ(hits[stratum], 1) << name << " seed " << seed << " stratum " << stratum;
        }
      }
    }
  }
}

TEST(Stratified, EveryCellHoldsExactlyOnePoint) {
  for (const auto& [name, k] :
       {std::pair{"Stratified", 3}, {"Reference", 10}, {"Stratified:5", 5}}) {
    const auto rule = findRule(name);
    ASSERT_EQ(rule->sampleCount(), std::size_t(k * k * k * k));
    for (std::uint64_t seed : {0ull, 42ull}) {
      const LinkSamples p = rule->samples(seed).points;
      std::vector<int> hits(rule->sampleCount(), 0);
      for (std::size_t q = 0; q < p.size(); ++q) {
        int cell = 0;
        for (double x : {p.s[q], p.t[q], p.u[q], p.v[q]}) {
          ASSERT_GE(x, 0.0);
          ASSERT_LT(x, 1.0);
          cell = cell * k + int(x * k);
        }
        ++hits[std::size_t(cell)];
      }
      for (std::size_t cell = 0; cell < hits.size(); ++cell) {
        ASSERT_EQ(hits[cell], 1) << name << " seed " << seed << " cell " << cell;
      }
    }
  }
}

std::vector<std::string> randomRuleNames() {
  std::vector<std::string> names;
  for (const auto& rule : namedRules()) {
    if (rule->isRandom()) names.push_back(rule->name());
  }
  return names;
}

// The reproducibility contract of Stratified:k written out with scalar code: cell
// c = ((i_s k + i_t) k + i_u) k + i_v takes its jitter from Philox blocks 2c and 2c+1 of
// stream randomStream("Stratified Monte Carlo", 0) under the seed's key, point = min((i + uniform) / k, 1 - 2^-53) per axis.
// Point p is cell p for odd k; for even k, p = 16 b + j lies in the cell with digits
// 2 b_x + (bit x of j), b's digits in base k / 2 (stratified.h).
// The rule's samples and its stream (any range of points) must give exactly these points.
std::array<std::size_t, 4> documentedDigits(std::size_t p, std::size_t k) {
  if (k % 2 != 0) return {p / (k * k * k), p / (k * k) % k, p / k % k, p % k};
  const std::size_t h = k / 2, b = p / 16, j = p % 16;
  return {2 * (b / (h * h * h)) + (j >> 3 & 1), 2 * (b / (h * h) % h) + (j >> 2 & 1),
          2 * (b / h % h) + (j >> 1 & 1), 2 * (b % h) + (j & 1)};
}

TEST(Stratified, PointsFollowTheDocumentedStreamAndTheStreamMatchesTheSamples) {
  for (const auto& [name, k] : {std::pair{"Stratified", 3}, {"Stratified:7", 7},
                                {"Reference", 10}, {"Stratified:16", 16}, {"Stratified:2", 2}}) {
    const auto rule = findRule(name);
    const std::uint64_t seed = 0x5eed0000ull + std::uint64_t(k);
    const RuleSamples samples = rule->samples(seed);
    const std::size_t count = samples.size();
    const double below = std::nextafter(1.0, 0.0);
    for (std::size_t p = 0; p < count; ++p) {
      const std::array<std::size_t, 4> digits = documentedDigits(p, std::size_t(k));
      const std::size_t c = ((digits[0] * k + digits[1]) * k + digits[2]) * k + digits[3];
      const std::uint32_t stream = randomStream("Stratified Monte Carlo", 0);
      const PhiloxCounter even = philox4x32({std::uint32_t(2 * c), 0, stream, 0}, philoxKey(seed));
      const PhiloxCounter odd =
          philox4x32({std::uint32_t(2 * c + 1), 0, stream, 0}, philoxKey(seed));
      const double jitter[4] = {uniformFromWords(even[0], even[1]),
                                uniformFromWords(even[2], even[3]),
                                uniformFromWords(odd[0], odd[1]), uniformFromWords(odd[2], odd[3])};
      const double* axes[4] = {samples.points.s.data(), samples.points.t.data(),
                               samples.points.u.data(), samples.points.v.data()};
      for (int axis = 0; axis < 4; ++axis) {
        const double expected = std::min((double(digits[axis]) + jitter[axis]) * (1.0 / k), below);
        ASSERT_EQ(axes[axis][p], expected) << name << " point " << p << " axis " << axis;
      }
    }
    const auto points = rule->pointStream(seed);
    ASSERT_TRUE(points) << name;
    ASSERT_EQ(points->size(), count);
    for (const auto& [first, size] : {std::pair<std::size_t, std::size_t>{0, count},
                                      {count / 3, count / 2 + 1},
                                      {count - 1, 1}}) {
      std::vector<double> s(size), t(size), u(size), v(size);
      points->fill(first, size, s.data(), t.data(), u.data(), v.data());
      for (std::size_t i = 0; i < size; ++i) {
        ASSERT_EQ(s[i], samples.points.s[first + i]) << name << " point " << first + i;
        ASSERT_EQ(t[i], samples.points.t[first + i]) << name << " point " << first + i;
        ASSERT_EQ(u[i], samples.points.u[first + i]) << name << " point " << first + i;
        ASSERT_EQ(v[i], samples.points.v[first + i]) << name << " point " << first + i;
      }
    }
  }
}

TEST(RandomRules, SameSeedSamePointsOnEveryThreadAndDifferentSeedsDiffer) {
  // Every random rule of the registry, whatever it holds.
  const auto names = randomRuleNames();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    const auto rule = findRule(name);
    const LinkSamples first = rule->samples(17).points;
    const LinkSamples again = rule->samples(17).points;
    LinkSamples fromThread;
    std::thread worker([&] { fromThread = rule->samples(17).points; });
    worker.join();
    const LinkSamples other = rule->samples(18).points;
    EXPECT_EQ(first.s, again.s) << name;
    EXPECT_EQ(first.v, again.v) << name;
    EXPECT_EQ(first.s, fromThread.s) << name;
    EXPECT_EQ(first.t, fromThread.t) << name;
    EXPECT_EQ(first.u, fromThread.u) << name;
    EXPECT_EQ(first.v, fromThread.v) << name;
    EXPECT_NE(first.s, other.s) << name;
    EXPECT_NE(first.u, other.u) << name;
  }
}

// Mean over 400 seeds against the closed-form form factor of parallel squares (degree 0) and
// against a high-order Gauss product (degree 2), within 4.5 standard errors of the mean.
TEST(RandomRules, MeanOverSeedsAgreesWithGold) {
  const Link link = parallelSquares();
  const double exactFormFactor = analytic::parallelRectangles(1, 1, 1);
  const LinkIntegral gold = PreparedRule(findRule("Gauss:12x12x12x12"), 2).integrate(link);
  ASSERT_NEAR(gold.formFactor, exactFormFactor, 1e-9);
  constexpr int kTrials = 400;
  constexpr double kStandardErrors = 4.5;
  // Every random rule of the registry, and two parametrised variants.
  std::vector<std::string> names = randomRuleNames();
  names.push_back("MonteCarlo:20");
  names.push_back("NRook:7");
  for (const std::string& name : names) {
    const PreparedRule prepared(findRule(name), 2);
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(9, 9), squares = sum;
    for (int seed = 0; seed < kTrials; ++seed) {
      const LinkIntegral draw = prepared.integrate(link, std::uint64_t(seed));
      sum += draw.coupling;
      squares += draw.coupling.cwiseAbs2();
    }
    const Eigen::MatrixXd mean = sum / kTrials;
    const Eigen::MatrixXd standardError =
        ((squares / kTrials - mean.cwiseAbs2()) * (kTrials / (kTrials - 1.0))).cwiseSqrt() /
        std::sqrt(double(kTrials));
    for (int a = 0; a < 9; ++a) {
      for (int b = 0; b < 9; ++b) {
        EXPECT_LT(std::fabs(mean(a, b) - gold.coupling(a, b)),
                  kStandardErrors * standardError(a, b) + 1e-15)
            << name << " K[" << a << "][" << b << "] mean " << mean(a, b) << " gold "
            << gold.coupling(a, b) << " standard error " << standardError(a, b);
      }
    }
    EXPECT_LT(std::fabs(mean(0, 0) - exactFormFactor), kStandardErrors * standardError(0, 0))
        << name;
  }
}

TEST(RandomRules, ParametrisedFormsRejectBadParameters) {
  for (const char* bad : {"NRook:0", "NRook:x", "MonteCarlo:-3", "Stratified:57",
                          "Stratified:", "MonteCarlo:12abc"}) {
    EXPECT_ANY_THROW(findRule(bad)) << bad;
  }
  EXPECT_EQ(findRule("Stratified:4")->sampleCount(), 256u);
  EXPECT_EQ(findRule("MonteCarlo:17")->sampleCount(), 17u);
}

// Stream numbers are derived from the family's name (quadrature/random/seeds.h): the
// registered random families, with four purposes each, must not share a stream, and the
// same name must always give the same stream.
TEST(RandomRules, EveryRegisteredFamilyDrawsFromItsOwnStreams) {
  std::set<std::string> families;
  for (const std::string& name : randomRuleNames()) families.insert(findRule(name)->family());
  ASSERT_GE(families.size(), 3u);
  std::set<std::uint32_t> streams;
  for (const std::string& family : families) {
    for (std::uint32_t purpose = 0; purpose < 4; ++purpose) {
      EXPECT_TRUE(streams.insert(randomStream(family, purpose)).second) << family << " " << purpose;
      EXPECT_EQ(randomStream(family, purpose), randomStream(std::string(family), purpose));
    }
  }
  static_assert(randomStream("Monte Carlo", 0) != randomStream("Monte Carlo", 1));
}

}  // namespace
}  // namespace radquad
