#include "reference/exact_gold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "kernel/input_error.h"
#include "reference/critical_line_cubature.h"
#include "reference/critical_segments.h"
#include "reference/genz_malik.h"
#include "reference/outer_integrand.h"

namespace radquad {
namespace {

using namespace exact_gold_detail;

// One run of an outer integration: its values, error estimates, whether it met its
// tolerance, and the receiver points it took.
struct OuterRun {
  std::vector<double> value, error;
  bool converged = false;
  std::uint64_t points = 0;
};

// The inner integrals' share of the tolerance (OuterIntegrand takes them to it) and their
// rounding, both relative to K's largest entry, added to every outer estimate (exactGold).
constexpr double kInnerShare = 1e-2;
constexpr double kRounding = 1e-13;

// An outer run confirmed by a second one: `run(grid, factor, budget)` integrates to `factor`
// of its tolerance from a grid of grid x grid pieces within `budget` points. Where a kink of
// the inner integral lies at the same place in many pieces (a penumbra nearly along an axis),
// a piece's two rules can agree while both are wrong, coherently: on small far sources behind
// a blocker the actual error of Genz-Malik from 8 x 8 regions stopped falling at about 2e-7
// of K's largest entry, 200 times its estimate at 1e-9, and runs from 11 x 11 and 13 x 13
// regions missed by other amounts; the jump lines, whose pieces halve as Genz-Malik's regions
// do, missed by 1e-10 where they estimated 1e-12. The second run starts from grid + 3 pieces
// a side, so that no piece of one lines up with a piece of the other but at the square's
// border. Both go to half the tolerance; they are confirmed when they agree within their
// summed estimates, and otherwise run once more at a twentieth of it. The first run's value
// is given, with the error max(its estimate, the runs' difference + the second's estimate):
// a bound whenever either run's estimate holds.
template <class Run>
OuterRun confirmedRun(const Run& run, int grid, std::uint64_t budget, bool& confirmed) {
  const int second = grid + 3;
  const std::uint64_t smallest = std::uint64_t(second) * std::uint64_t(second) * kGenzMalikPoints;
  OuterRun out;
  confirmed = false;
  for (const double factor : {0.5, 0.05}) {
    const std::uint64_t left = budget > out.points ? budget - out.points : 0;
    if (left < 2 * smallest) break;
    const OuterRun first = run(grid, factor, left / 2);
    const OuterRun other = run(second, factor, std::max(smallest, left - first.points));
    out.points += first.points + other.points;
    out.value = first.value;
    out.error.resize(first.value.size());
    confirmed = first.converged && other.converged;
    for (std::size_t v = 0; v < first.value.size(); ++v) {
      const double difference = std::abs(first.value[v] - other.value[v]);
      confirmed = confirmed && difference <= first.error[v] + other.error[v];
      out.error[v] = std::max(first.error[v], difference + other.error[v]);
    }
    out.converged = confirmed;
    if (confirmed) break;
  }
  return out;
}

// Whether every receiver point lies strictly in front of the source's plane (the receiver is
// a parallelogram: its corners decide). Then S', the source clipped by the receiver's plane,
// is the same polygon from every receiver point and its integral is analytic over the receiver.
bool receiverInFrontOfSource(const Link& link) {
  for (const Eigen::Vector3d& corner : link.receiver.corners()) {
    if (!(link.source.normal.dot(corner - link.source.origin) > 0.0)) return false;
  }
  return true;
}

// K's unoccluded part, the outer integral of the inner integrals over S' alone (the link
// without its occluders): analytic over the receiver when it lies in front of the source's
// plane, so Gauss-Legendre products of rising order converge exponentially. The error given
// is the difference of the last two orders, a bound on the coarser one (conservative for the
// finer one, returned); an order is accepted from 8 points per axis on, so that at least
// three orders were seen. That difference sees the outer rule's error only: the inner
// integrals are taken to about 1e-14 (the 12-point edge rule), not to a hundredth of the
// tolerance as elsewhere, whose error, smooth in x and so the same in every order, it would
// not see. They are few (260 receiver points on most links), so that costs little.
class UnoccludedPart {
 public:
  UnoccludedPart(const Link& link, int degree)
      : bare_{link.receiver, link.source, nullptr},
        integrand_(bare_, degree, kTightInnerTolerance),
        values_(std::size_t(integrand_.functions * integrand_.functions)) {}

  // Runs the next orders until every entry's error is at most min(relative * the largest
  // |entry|, absolute); false when the last order is reached first.
  bool refine(double relative, double absolute) {
    for (;;) {
      if (next_ > 0 && kOrders[next_ - 1] >= 8 &&
          largestAbs(error) <= std::min(relative * largestAbs(value), absolute)) {
        return true;
      }
      if (next_ == std::size(kOrders)) return false;
      std::vector<double> coarser = std::move(value);
      value = gaussProduct(integrand_, kOrders[next_++]);
      if (!integrand_.finite()) throw ComputationError("exact gold: the inner integral was not finite");
      if (coarser.empty()) {
        error.assign(values_, std::numeric_limits<double>::infinity());
      } else {
        for (std::size_t v = 0; v < values_; ++v) error[v] = std::abs(value[v] - coarser[v]);
      }
    }
  }

  std::vector<double> value, error;
  std::uint64_t points() const { return integrand_.points; }

 private:
  static constexpr int kOrders[] = {4, 6, 8, 12, 16, 24, 32};
  // OuterIntegrand takes its inner integrals to a hundredth of this: 1e-14.
  static constexpr double kTightInnerTolerance = 1e-12;

  Link bare_;
  OuterIntegrand integrand_;
  std::size_t values_;
  std::size_t next_ = 0;
};

}  // namespace

const char* exactOuterMethodName(ExactOuterMethod method) {
  switch (method) {
    case ExactOuterMethod::criticalLines: return "critical lines";
    case ExactOuterMethod::jumpLines: return "jump lines";
    case ExactOuterMethod::genzMalik: return "genz-malik";
  }
  return "unknown";
}

ExactGold exactGold(const Link& link, int degree, const ExactGoldOptions& options) {
  validateBasisDegree(degree);
  if (!(options.tolerance > 0.0)) throw InputError("exact gold: tolerance must be positive");
  OuterIntegrand integrand(link, degree, options.tolerance);
  integrand.progress = options.progress;
  const unsigned values = unsigned(integrand.functions * integrand.functions);
  std::vector<double> value(values), error(values);
  ExactGold gold;
  // The shaft's occluders as one worker culled them (instead of culling once more).
  const std::vector<std::vector<Eigen::Vector3d>>& candidates =
      integrand.workers.local().visibility.candidates();
  // The unoccluded part apart (degree >= 1; exact_gold.h): K = K_free + K_rest, K_rest the
  // integral over minus the shadows' union. K_free first, to a twentieth of the tolerance of
  // its own largest entry; K_rest then to kRestShare of the tolerance of the whole's largest
  // entry; K_free's error is then held to the rest of the tolerance (below).
  constexpr double kRestShare = 0.9;
  std::optional<UnoccludedPart> free;
  std::uint64_t spent = 0;  // points of an unoccluded part given up
  if (options.unoccludedApart && degree >= 1 && !candidates.empty() && receiverInFrontOfSource(link)) {
    free.emplace(link, degree);
    const double inf = std::numeric_limits<double>::infinity();
    // Not converged by the last order (the receiver nearly touching S'): one integral.
    if (free->refine(0.05 * options.tolerance, inf)) {
      integrand.shadowsOnly = true;
    } else {
      spent = free->points();
      free.reset();
    }
  }
  // The inner integrals err by up to their accuracy (a hundredth of the tolerance, of a
  // point's largest moment; source_moments.h; at degree 0 Lambert's formula is exact but for
  // rounding), smoothly over the receiver: the outer rules' differences do not see that error.
  // The gold vouches for nothing finer: innerFloor of K's largest entry is added to every
  // estimate, and the outer rules aim at the rest of the tolerance. (Critical lines that met
  // the breakpoints alone with estimates of 1e-15 differed by up to 2e-11 from runs by the
  // other outer methods 1,000 times tighter; tests/reference/gold_honesty_test.cpp.)
  const double innerFloor = std::max(kRounding, kInnerShare * options.tolerance);
  const double outerShare = 1.0 - innerFloor / options.tolerance;
  const double share = (free ? kRestShare : 1.0) * outerShare;
  // Genz-Malik's own estimate (its embedded degree-5 rule) cannot see what no point of a
  // region samples, such as a thin shadow between its points: started from the whole square,
  // a run at the study's 3e-4 stopped early on 1 of 24 of the study's partial links at each
  // degree with an actual error 2.4 (degree 0) and 1.4 (degree 2) times its estimate
  // (tests/reference/gold_honesty_test.cpp, against critical-line golds at 1e-7). Started
  // from 8 x 8 regions (1,088 points), none failed, the worst actual error 0.16 and 0.33 of
  // the estimate; 4 x 4 and 2 x 2 passed too on those links, and 8 x 8 costs about as many
  // points as they do at 3e-4 (2,300 and 3,500 a link on average, against 1,800 and 3,400).
  // Below confirmBelow the two methods without the critical segments as breakpoints are
  // confirmed by a second run (confirmedRun).
  auto genzMalik = [&](int grid, double factor, std::uint64_t budget) {
    GenzMalikOptions genz;
    genz.tolerance = factor * share * options.tolerance;
    genz.initialGrid = grid;
    genz.maxEvaluations = budget;
    if (free) genz.baseline = free->value;
    const std::uint64_t before = integrand.points;
    GenzMalikResult run = genzMalik2d(
        values,
        [&](std::size_t count, const double* points, double* out) {
          evaluateBatch(integrand, count, points, out);
        },
        genz);
    return OuterRun{std::move(run.value), std::move(run.error), run.converged,
                    integrand.points - before};
  };
  const std::vector<ReceiverSegment> contact = contactSegments(link.receiver, candidates);
  auto jumpLines = [&](int grid, double factor, std::uint64_t budget) {
    ExactGoldOptions lines = options;
    lines.tolerance = factor * options.tolerance;
    lines.maxEvaluations = budget;
    CriticalLineCubature cubature(integrand, contact, lines, grid);
    cubature.setBaseline(free ? free->value : std::vector<double>{}, share);
    OuterRun run;
    run.converged = cubature.run(run.value, run.error);
    run.points = cubature.points();
    return run;
  };
  ExactOuterMethod method = options.outer;
  std::uint64_t outerPoints = 0;
  if (method == ExactOuterMethod::criticalLines) {
    std::vector<ReceiverSegment> segments = criticalSegments(link.receiver, link.source, candidates);
    gold.criticalSegments = segments.size();
    CriticalLineCubature cubature(integrand, std::move(segments), options);
    cubature.setBaseline(free ? free->value : std::vector<double>{}, share);
    // Many segments make the breakpoints' product costly (floor ~ segments^2): then the
    // bisection of Genz-Malik, linear in the segments' length, is cheaper.
    // Genz-Malik's points grow as tolerance^(-1/2), the floor not at all: the threshold
    // scales so.
    const double floorLimit =
        double(degree == 0 ? options.maxFloorPoints : options.maxFloorPointsHigherDegrees);
    double threshold = floorLimit * std::sqrt(1e-7 / options.tolerance);
    // Where the inner integral jumps (contactSegments), Genz-Malik's error falls only as fast
    // as its regions along the jump shrink, its points as 1 / tolerance: at 1e-7 it did not
    // converge in 4,000,000 points on such study links, where the critical lines, which take
    // the jump as a breakpoint, did in 140,000 to 440,000.
    if (!contact.empty()) {
      threshold = std::max(threshold, 100.0 * floorLimit * (1e-7 / options.tolerance));
    }
    if (cubature.floorWithin(threshold)) {
      cubature.run(value, error);
      outerPoints = cubature.points();
    } else {
      // Too many segments for their breakpoints. Where the inner integral jumps, Genz-Malik's
      // estimate is not to be trusted: a region's 17 points see a jump only as a difference
      // between them, and across the study's links its actual error reached 1.2 (degree 0)
      // and 5.3 (degree 2) times its estimate on a link with an occluder standing on the
      // receiver (the jump lines, below, met theirs). The jumps alone then stay breakpoints.
      method = contact.empty() ? ExactOuterMethod::genzMalik : ExactOuterMethod::jumpLines;
    }
  }
  if (method != ExactOuterMethod::criticalLines) {
    const auto run = [&](int grid, double factor, std::uint64_t budget) {
      return method == ExactOuterMethod::genzMalik ? genzMalik(grid, factor, budget)
                                                   : jumpLines(grid, factor, budget);
    };
    OuterRun result = options.tolerance < options.confirmBelow
                          ? confirmedRun(run, options.initialGrid, options.maxEvaluations, gold.confirmed)
                          : run(options.initialGrid, 1.0, options.maxEvaluations);
    value = std::move(result.value);
    error = std::move(result.error);
    outerPoints = result.points;
  }
  integrand.points = outerPoints;
  if (!integrand.finite()) throw ComputationError("exact gold: the inner integral was not finite");
  if (free) {
    // K_free's error must fit the tolerance's remaining share of the whole's largest entry;
    // where the shadows take most of K, it was computed too loosely: higher orders.
    const double allowed =
        (1.0 - kRestShare) * outerShare * options.tolerance * largestOfSum(free->value, value);
    if (largestAbs(free->error) > allowed &&
        !free->refine(std::numeric_limits<double>::infinity(), 0.5 * allowed)) {
      // The last order reached first: the whole integral at once instead.
      ExactGoldOptions together = options;
      together.unoccludedApart = false;
      ExactGold gold = exactGold(link, degree, together);
      gold.receiverPoints += integrand.points + free->points();
      return gold;
    }
    for (unsigned v = 0; v < values; ++v) {
      value[v] += free->value[v];
      error[v] += free->error[v];
    }
    integrand.points += free->points();
  }
  gold.unoccludedApart = free.has_value();
  integrand.points += spent;
  gold.outer = method;
  const int n = integrand.functions;
  gold.coupling.resize(n, n);
  gold.couplingError.resize(n, n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      gold.coupling(a, b) = value[std::size_t(a * n + b)];
      gold.couplingError(a, b) = error[std::size_t(a * n + b)];
    }
  }
  const double toFormFactor = std::sqrt(link.source.area / link.receiver.area);
  const double largest = gold.coupling.cwiseAbs().maxCoeff();
  gold.couplingError.array() += innerFloor * largest;
  gold.formFactor = gold.coupling(0, 0) * toFormFactor;
  gold.formFactorError = gold.couplingError(0, 0) * toFormFactor;
  gold.converged = gold.confirmed && gold.couplingError.maxCoeff() <= options.tolerance * largest;
  gold.receiverPoints = integrand.points;
  // Every worker culled the same shaft: read the count from one instead of culling again.
  for (const Worker& worker : integrand.workers) {
    gold.polygonUnions += worker.visibility.statistics().unions;
    gold.candidateOccluders = worker.visibility.candidateCount();
  }
  return gold;
}

}  // namespace radquad
