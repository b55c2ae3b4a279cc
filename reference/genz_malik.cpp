#include "reference/genz_malik.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>

#include "kernel/input_error.h"

namespace radquad {
namespace {

// The rule for n = 2 (Genz and Malik 1980): the degree-7 rule's abscissae as fractions of
// the half-width and its weights per point of each orbit (as fractions of the region's area),
// then the embedded degree-5 rule's weights (it leaves out the fifth orbit).
const double kLambda2 = std::sqrt(9.0 / 70.0);
const double kLambda4 = std::sqrt(9.0 / 10.0);
const double kLambda5 = std::sqrt(9.0 / 19.0);
constexpr double kN = 2.0;
constexpr double kWeight1 = (12824.0 - 9120.0 * kN + 400.0 * kN * kN) / 19683.0;
constexpr double kWeight2 = 980.0 / 6561.0;
constexpr double kWeight3 = (1820.0 - 400.0 * kN) / 19683.0;
constexpr double kWeight4 = 200.0 / 19683.0;
constexpr double kWeight5 = 6859.0 / 19683.0 / 4.0;
constexpr double kEmbedded1 = (729.0 - 950.0 * kN + 50.0 * kN * kN) / 729.0;
constexpr double kEmbedded2 = 245.0 / 486.0;
constexpr double kEmbedded3 = (265.0 - 100.0 * kN) / 1458.0;
constexpr double kEmbedded4 = 25.0 / 729.0;
// The fourth difference along an axis compares the second differences at lambda2 and lambda4,
// the latter scaled by (lambda2 / lambda4)^2.
constexpr double kDifferenceRatio = 1.0 / 7.0;

struct Region {
  double centre[2];
  double half[2];
  std::vector<double> value, error;
  double worst = 0.0;  // the largest component error
  int split = 0;       // the axis to halve next
};

// The 17 points of a region in the order fold() reads them: the centre; per axis the pairs
// at lambda2 and at lambda4; the four (+-lambda4, +-lambda4); the four (+-lambda5, +-lambda5).
void regionPoints(const Region& region, double* out) {
  const double cs = region.centre[0], ct = region.centre[1];
  const double hs = region.half[0], ht = region.half[1];
  int k = 0;
  auto put = [&](double s, double t) {
    out[2 * k] = s;
    out[2 * k + 1] = t;
    ++k;
  };
  put(cs, ct);
  put(cs - kLambda2 * hs, ct);
  put(cs + kLambda2 * hs, ct);
  put(cs - kLambda4 * hs, ct);
  put(cs + kLambda4 * hs, ct);
  put(cs, ct - kLambda2 * ht);
  put(cs, ct + kLambda2 * ht);
  put(cs, ct - kLambda4 * ht);
  put(cs, ct + kLambda4 * ht);
  for (double a : {-1.0, 1.0}) {
    for (double b : {-1.0, 1.0}) put(cs + a * kLambda4 * hs, ct + b * kLambda4 * ht);
  }
  for (double a : {-1.0, 1.0}) {
    for (double b : {-1.0, 1.0}) put(cs + a * kLambda5 * hs, ct + b * kLambda5 * ht);
  }
}

// The region's integrals, errors and axis to halve from its 17 points' values.
void fold(Region& region, const double* f, std::size_t values) {
  const double area = 4.0 * region.half[0] * region.half[1];
  region.value.assign(values, 0.0);
  region.error.assign(values, 0.0);
  region.worst = 0.0;
  double difference[2] = {0.0, 0.0};
  auto at = [&](int point, std::size_t v) { return f[std::size_t(point) * values + v]; };
  for (std::size_t v = 0; v < values; ++v) {
    const double centre = at(0, v);
    double sum2 = 0.0, sum3 = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
      const int base = 1 + 4 * axis;
      const double inner = at(base, v) + at(base + 1, v);
      const double outer = at(base + 2, v) + at(base + 3, v);
      sum2 += inner;
      sum3 += outer;
      difference[axis] +=
          std::abs((inner - 2.0 * centre) - kDifferenceRatio * (outer - 2.0 * centre));
    }
    double sum4 = 0.0, sum5 = 0.0;
    for (int p = 9; p < 13; ++p) sum4 += at(p, v);
    for (int p = 13; p < 17; ++p) sum5 += at(p, v);
    const double seventh =
        kWeight1 * centre + kWeight2 * sum2 + kWeight3 * sum3 + kWeight4 * sum4 + kWeight5 * sum5;
    const double fifth = kEmbedded1 * centre + kEmbedded2 * sum2 + kEmbedded3 * sum3 + kEmbedded4 * sum4;
    region.value[v] = area * seventh;
    region.error[v] = area * std::abs(seventh - fifth);
    region.worst = std::max(region.worst, region.error[v]);
  }
  // The axis of larger fourth difference; on a tie (a polynomial the rule integrates
  // exactly, say) the wider one, then s.
  const double tie = 1e-10 * std::max(difference[0], difference[1]);
  if (std::abs(difference[0] - difference[1]) <= tie) {
    region.split = region.half[1] > region.half[0] ? 1 : 0;
  } else {
    region.split = difference[1] > difference[0] ? 1 : 0;
  }
}

}  // namespace

GenzMalikResult genzMalik2d(std::size_t values, const BatchIntegrand& evaluate,
                            const GenzMalikOptions& options) {
  if (values == 0) throw InputError("genz-malik: no integrands");
  if (!(options.tolerance > 0.0)) throw InputError("genz-malik: tolerance must be positive");
  if (options.initialGrid < 1 || options.initialGrid > 1024) {
    throw InputError("genz-malik: the initial grid must have 1 to 1024 regions per axis");
  }
  if (options.batchRegions < 1) throw InputError("genz-malik: a batch needs a region");
  if (!options.baseline.empty() && options.baseline.size() != values) {
    throw InputError("genz-malik: the baseline must have one value per integrand");
  }
  GenzMalikResult result;
  std::vector<Region> regions;
  std::vector<double> points, out;
  // Evaluates the regions listed and folds their values.
  auto run = [&](const std::vector<std::size_t>& listed) {
    points.resize(listed.size() * 2 * kGenzMalikPoints);
    out.resize(listed.size() * kGenzMalikPoints * values);
    for (std::size_t k = 0; k < listed.size(); ++k) {
      regionPoints(regions[listed[k]], points.data() + k * 2 * kGenzMalikPoints);
    }
    evaluate(listed.size() * kGenzMalikPoints, points.data(), out.data());
    result.points += listed.size() * kGenzMalikPoints;
    for (std::size_t k = 0; k < listed.size(); ++k) {
      fold(regions[listed[k]], out.data() + k * kGenzMalikPoints * values, values);
    }
  };
  const int grid = options.initialGrid;
  const std::uint64_t initialPoints = std::uint64_t(grid) * std::uint64_t(grid) * kGenzMalikPoints;
  if (initialPoints > options.maxEvaluations) {
    throw InputError("genz-malik: the evaluation budget is smaller than the initial grid's points");
  }
  std::vector<std::size_t> listed;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      Region region;
      region.half[0] = region.half[1] = 0.5 / grid;
      region.centre[0] = (2 * i + 1) * region.half[0];
      region.centre[1] = (2 * j + 1) * region.half[1];
      listed.push_back(regions.size());
      regions.push_back(std::move(region));
    }
  }
  run(listed);
  // The largest error first; equal errors by index, so the order is the values' alone.
  auto less = [&](std::size_t a, std::size_t b) {
    return regions[a].worst < regions[b].worst || (regions[a].worst == regions[b].worst && a > b);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(less)> heap(less);
  for (std::size_t k = 0; k < regions.size(); ++k) heap.push(k);
  std::vector<double> remaining(values);
  // The sums are kept up to date as regions are halved (a parent's terms out, its children's
  // in), and summed afresh over every region before convergence is declared, so rounding in
  // the updates never decides it.
  auto sumAll = [&] {
    result.value.assign(values, 0.0);
    result.error.assign(values, 0.0);
    for (const Region& region : regions) {
      for (std::size_t v = 0; v < values; ++v) {
        result.value[v] += region.value[v];
        result.error[v] += region.error[v];
      }
    }
  };
  sumAll();
  bool fresh = true;  // the sums are summed afresh
  for (;;) {
    double largest = 0.0, worst = 0.0;
    for (std::size_t v = 0; v < values; ++v) {
      const double known = options.baseline.empty() ? 0.0 : options.baseline[v];
      largest = std::max(largest, std::abs(known + result.value[v]));
      worst = std::max(worst, result.error[v]);
    }
    if (!std::isfinite(largest) || !std::isfinite(worst)) break;
    const double target = options.tolerance * largest;
    if (worst <= target) {
      if (fresh) {
        result.converged = true;
        break;
      }
      sumAll();
      fresh = true;
      continue;
    }
    // The regions to halve: the largest errors first, until what is left fits the
    // tolerance, the batch is full or the budget would be overrun.
    const std::uint64_t left = options.maxEvaluations - result.points;
    const std::size_t affordable = std::size_t(left / (2 * kGenzMalikPoints));
    const std::size_t cap = std::min(options.batchRegions, affordable);
    if (cap == 0) break;
    remaining = result.error;
    listed.clear();
    while (!heap.empty() && listed.size() < 2 * cap) {
      const std::size_t k = heap.top();
      heap.pop();
      Region& parent = regions[k];
      for (std::size_t v = 0; v < values; ++v) {
        remaining[v] -= parent.error[v];
        result.value[v] -= parent.value[v];
        result.error[v] -= parent.error[v];
      }
      const int axis = parent.split;
      parent.half[axis] *= 0.5;
      Region child = parent;
      parent.centre[axis] -= parent.half[axis];
      child.centre[axis] += parent.half[axis];
      listed.push_back(k);
      listed.push_back(regions.size());
      regions.push_back(std::move(child));
      if (*std::max_element(remaining.begin(), remaining.end()) <= target) break;
    }
    run(listed);
    for (std::size_t k : listed) {
      heap.push(k);
      for (std::size_t v = 0; v < values; ++v) {
        result.value[v] += regions[k].value[v];
        result.error[v] += regions[k].error[v];
      }
    }
    fresh = false;
  }
  if (!result.converged) sumAll();
  return result;
}

}  // namespace radquad
