#include "quadrature/rules/stratified.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "quadrature/random/philox.h"
#include "quadrature/random/seeds.h"

namespace radquad {

StratifiedRule::StratifiedRule(int strataPerAxis, std::string name)
    : strata_(strataPerAxis),
      name_(name.empty() ? "Stratified:" + std::to_string(strataPerAxis) : std::move(name)) {}

std::size_t StratifiedRule::sampleCount() const {
  const std::size_t k = std::size_t(strata_);
  return k * k * k * k;
}

std::string StratifiedRule::citation() const {
  return "Neyman 1934 (stratified sampling); Cook 1986 (jittering); Gershbein 1995, sections 3 "
         "and 4";
}

void StratifiedRule::fillPoints(std::uint64_t seed, std::size_t first, std::size_t count,
                                double* __restrict s, double* __restrict t, double* __restrict u,
                                double* __restrict v) const {
  const double k = double(strata_);
  const double width = 1.0 / k;
  const double below = std::nextafter(1.0, 0.0);
  if (strata_ % 2 != 0) {
    // Cell order: point p is cell p, whose jitter is Philox blocks 2p and 2p+1 (eight words,
    // two per coordinate).
    philoxUniformQuads(philoxKey(seed), randomStream(kFamily, 0),
                       std::uint32_t(first), count, s, t, u, v);
    // The cell's digits (i_s, i_t, i_u, i_v) in base k, as exact small integers in doubles
    // so the loop vectorises: q = floor((c + 1/2) / k) (a truncation, the value being
    // positive) is exact, since (c + 1/2) / k lies at least 1/(2k) >= 1/112 from an integer
    // and c < 56^4 < 2^24 keeps the rounding error below 1e-8.
    const double inverse = 1.0 / k;
#pragma GCC ivdep
    for (std::size_t row = 0; row < count; ++row) {
      const double cell = double(first + row);
      const double q1 = double(std::int32_t((cell + 0.5) * inverse));  // c div k
      const double q2 = double(std::int32_t((q1 + 0.5) * inverse));    // c div k^2
      const double q3 = double(std::int32_t((q2 + 0.5) * inverse));    // c div k^3 = i_s
      // std::min(x, below), written out so that the loop vectorises.
      const double ps = (q3 + s[row]) * width, pt = ((q2 - q3 * k) + t[row]) * width;
      const double pu = ((q1 - q2 * k) + u[row]) * width, pv = ((cell - q1 * k) + v[row]) * width;
      s[row] = below < ps ? below : ps;
      t[row] = below < pt ? below : pt;
      u[row] = below < pu ? below : pu;
      v[row] = below < pv ? below : pv;
    }
    return;
  }
  // Even k: block order (stratified.h). Point p = 16 b + i lies in block b, whose digits
  // (b_s, b_t, b_u, b_v) in base h = k / 2 are taken as above, and its cell's digits are
  // 2 b_x + (bit x of i): i's bits 3, 2, 1, 0 for s, t, u, v.
  const double h = 0.5 * k;
  const double inverse = 1.0 / h;
  constexpr std::size_t kChunk = 256;
  alignas(64) std::uint32_t cells[kChunk];
  alignas(64) double digits[4][kChunk];
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const std::size_t rows = std::min(kChunk, count - begin);
    for (std::size_t row = 0; row < rows; ++row) {
      const std::size_t point = first + begin + row;
      const double block = double(point >> 4);
      const std::uint32_t inner = std::uint32_t(point & 15u);
      const double q1 = double(std::int32_t((block + 0.5) * inverse));  // b div h
      const double q2 = double(std::int32_t((q1 + 0.5) * inverse));     // b div h^2
      const double q3 = double(std::int32_t((q2 + 0.5) * inverse));     // b div h^3 = b_s
      const double is = 2.0 * q3 + double((inner >> 3) & 1u);
      const double it = 2.0 * (q2 - q3 * h) + double((inner >> 2) & 1u);
      const double iu = 2.0 * (q1 - q2 * h) + double((inner >> 1) & 1u);
      const double iv = 2.0 * (block - q1 * h) + double(inner & 1u);
      digits[0][row] = is;
      digits[1][row] = it;
      digits[2][row] = iu;
      digits[3][row] = iv;
      cells[row] = std::uint32_t(((is * k + it) * k + iu) * k + iv);  // exact: below 2^24
    }
    double* ws = s + begin;
    double* wt = t + begin;
    double* wu = u + begin;
    double* wv = v + begin;
    philoxUniformQuadsAt(philoxKey(seed), randomStream(kFamily, 0), cells, rows, ws, wt, wu, wv);
    for (std::size_t row = 0; row < rows; ++row) {
      const double ps = (digits[0][row] + ws[row]) * width, pt = (digits[1][row] + wt[row]) * width;
      const double pu = (digits[2][row] + wu[row]) * width, pv = (digits[3][row] + wv[row]) * width;
      ws[row] = below < ps ? below : ps;
      wt[row] = below < pt ? below : pt;
      wu[row] = below < pu ? below : pu;
      wv[row] = below < pv ? below : pv;
    }
  }
}

void StratifiedRule::drawSamples(std::uint64_t seed, RuleSamples& out) const {
  const std::size_t count = sampleCount();
  resizeEqualWeights(count, out);
  LinkSamples& p = out.points;
  fillPoints(seed, 0, count, p.s.data(), p.t.data(), p.u.data(), p.v.data());
}

namespace {

class StratifiedPointStream : public PointStream {
 public:
  StratifiedPointStream(const StratifiedRule& rule, std::uint64_t seed)
      : rule_(rule), seed_(seed) {}
  std::size_t size() const override { return rule_.sampleCount(); }
  void fill(std::size_t first, std::size_t count, double* s, double* t, double* u,
            double* v) const override {
    rule_.fillPoints(seed_, first, count, s, t, u, v);
  }

 private:
  const StratifiedRule& rule_;
  std::uint64_t seed_;
};

}  // namespace

std::unique_ptr<PointStream> StratifiedRule::pointStream(std::uint64_t seed) const {
  return std::make_unique<StratifiedPointStream>(*this, seed);
}

std::shared_ptr<const Rule> makeStratifiedRule(const std::string& parameter) {
  return std::make_shared<StratifiedRule>(parseRuleParameter("Stratified", parameter, 1, 56, "k"));
}

}  // namespace radquad
