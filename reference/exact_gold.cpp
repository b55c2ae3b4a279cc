#include "reference/exact_gold.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <thread>
#include <limits>
#include <optional>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"
#include "kernel/progress_throttle.h"
#include "quadrature/gauss_legendre.h"
#include "reference/critical_segments.h"
#include "reference/exact_visibility.h"
#include "reference/adaptive_pieces.h"
#include "reference/gauss_kronrod.h"
#include "reference/genz_malik.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

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
void evaluateBatch(OuterIntegrand& integrand, std::size_t count, const double* points, double* out) {
  const std::size_t values = std::size_t(integrand.functions * integrand.functions);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Worker& worker = integrand.workers.local();
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        integrand.evaluate(worker, points[2 * k], points[2 * k + 1],
                                           out + k * values);
                      }
                    });
  integrand.points += count;
  integrand.report(integrand.points);
}

// The n x n Gauss-Legendre product over the receiver's square of the integrand's values,
// summed in a fixed order (the points spread over threads by evaluateBatch).
std::vector<double> gaussProduct(OuterIntegrand& integrand, int n) {
  const GaussLegendreRule& rule = gaussLegendreUnit(n);
  const std::size_t values = std::size_t(integrand.functions * integrand.functions);
  const std::size_t count = std::size_t(n) * std::size_t(n);
  std::vector<double> points(2 * count);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      points[2 * std::size_t(i * n + j)] = rule.nodes[std::size_t(i)];
      points[2 * std::size_t(i * n + j) + 1] = rule.nodes[std::size_t(j)];
    }
  }
  std::vector<double> out(count * values);
  evaluateBatch(integrand, count, points.data(), out.data());
  std::vector<double> sum(values, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double w = rule.weights[std::size_t(i)] * rule.weights[std::size_t(j)];
      const double* f = out.data() + std::size_t(i * n + j) * values;
      for (std::size_t v = 0; v < values; ++v) sum[v] += w * f[v];
    }
  }
  return sum;
}

// max_v |known[v] + value[v]| (known empty: max |value|): the size of a whole integral whose
// part `known` was integrated apart.
double largestOfSum(const std::vector<double>& known, const std::vector<double>& value) {
  if (known.empty()) return largestAbs(value);
  double largest = 0.0;
  for (std::size_t v = 0; v < value.size(); ++v) {
    largest = std::max(largest, std::abs(known[v] + value[v]));
  }
  return largest;
}

// The outer integral as iterated adaptive Gauss-Kronrod (gauss_kronrod.h) with the critical segments
// (critical_segments.h) as breakpoints: g(s) = int_0^1 f(s, t) dt along each line s = const,
// the breakpoints where the line crosses a segment; the outer integral of g over s, the
// breakpoints at the segments' ends and at segments along t. Between them the integrands are
// analytic (but for the three-edge events), and Gauss-Kronrod converges exponentially.
class CriticalLineCubature {
 public:
  // grid: besides the segments' breakpoints, the lines and the outer integral start from
  // `grid` equal pieces (1: none added).
  CriticalLineCubature(OuterIntegrand& integrand, std::vector<ReceiverSegment> segments,
                       const ExactGoldOptions& options, int grid = 1)
      : integrand_(integrand),
        pair_(options.kronrodPoints == 15 ||
                      (options.kronrodPoints == 0 && options.tolerance < 1e-6)
                  ? GaussKronrodPair::fifteenPoint()
                  : GaussKronrodPair::sevenPoint()),
        segments_(std::move(segments)),
        options_(options),
        grid_(grid),
        values_(std::size_t(integrand.functions * integrand.functions)) {
    std::vector<double> breaks = gridBreaks();
    for (const auto& segment : segments_) {
      breaks.push_back(segment.a.x());
      breaks.push_back(segment.b.x());
    }
    initial_ = piecesBetween(std::move(breaks));
  }

  // Whether the receiver points the initial breakpoints alone take (no bisection, the cost
  // floor) are at most `limit`. Counting stops once past it: each line's count sorts its
  // crossings with every segment, and a soup's tens of thousands of segments would make the
  // whole count cost more than the gold itself.
  bool floorWithin(double limit) const {
    const double perCell = double(pair_.points()) * double(pair_.points());
    if (perCell * double(initial_.size()) > limit) return false;
    double points = 0.0;
    for (const KronrodPiece& piece : initial_) {
      points += perCell * double(piecesBetween(lineBreaks(0.5 * (piece.a + piece.b))).size());
      if (points > limit) return false;
    }
    return true;
  }

  // A part of K known beforehand (the unoccluded part, with its own error): the run then
  // integrates the rest to `share` of the tolerance, relative to the whole K's largest entry.
  void setBaseline(std::vector<double> baseline, double share) {
    baseline_ = std::move(baseline);
    share_ = share;
  }

  // value, error: row-major (a * n + b). Returns whether the tolerance was met.
  bool run(std::vector<double>& value, std::vector<double>& error) {
    // The inner lines take an absolute tolerance, a share of tolerance * max |K|: K's size
    // comes first from a 16 x 16 Gauss product over the receiver. A poor estimate costs
    // points, not correctness: the summed errors (inner ones included) decide convergence.
    std::vector<KronrodPiece> pieces = initial_;
    double scale = estimateScale();
    std::vector<std::size_t> all(pieces.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    evaluateOuter(pieces, all, options_.innerShare * share_ * options_.tolerance * scale);
    for (;;) {
      sumPieces(pieces, values_, value, error);
      scale = largestOfSum(baseline_, value);
      const double target = share_ * options_.tolerance * scale;
      if (largestAbs(error) <= target) return true;
      if (points_ >= options_.maxEvaluations) return false;
      const double innerTolerance = options_.innerShare * target;
      integrand_.report(points_);
      if (!halveWorst(pieces, [&](std::vector<KronrodPiece>& next, const std::vector<std::size_t>& at) {
            std::vector<std::size_t> fresh;
            for (std::size_t k : at) {
              fresh.push_back(k);
              fresh.push_back(k + 1);
            }
            evaluateOuter(next, fresh, innerTolerance);
          })) {
        return false;
      }
    }
  }

  std::uint64_t points() const { return points_; }

 private:
  // 0, 1 and the grid's breakpoints k / grid.
  std::vector<double> gridBreaks() const {
    std::vector<double> breaks = {0.0, 1.0};
    for (int k = 1; k < grid_; ++k) breaks.push_back(double(k) / double(grid_));
    return breaks;
  }

  // The breakpoints of the line s = const: where it crosses a segment, and the grid's.
  std::vector<double> lineBreaks(double s) const {
    std::vector<double> breaks = crossingsAt(segments_, s);
    for (int k = 1; k < grid_; ++k) breaks.push_back(double(k) / double(grid_));
    return breaks;
  }

  // K's size, for the lines' first tolerance: a 16 x 16 Gauss product over the receiver.
  double estimateScale() {
    points_ += 16 * 16;
    return largestOfSum(baseline_, gaussProduct(integrand_, 16));
  }

  // The lines of every piece listed in `fresh` (one per point of the pair), computed in
  // parallel, each to the absolute `innerTolerance`. A line's result depends on its s only,
  // whatever the thread.
  void evaluateOuter(std::vector<KronrodPiece>& pieces, const std::vector<std::size_t>& fresh,
                     double innerTolerance) {
    const std::size_t m = std::size_t(pair_.points());
    const std::size_t lines = fresh.size() * m;
    // A line's points: at most maxLinePoints, and its share of what is left of the budget
    // (beyond its breakpoints' pieces, which it always takes).
    const std::uint64_t left =
        options_.maxEvaluations > points_ ? options_.maxEvaluations - points_ : 0;
    const std::uint64_t cap =
        std::min<std::uint64_t>(options_.maxLinePoints, left / std::max<std::size_t>(lines, 1));
    std::vector<KronrodPiece> lineResult(lines);
    std::vector<std::uint64_t> linePoints(lines, 0);
    // Progress is reported from the calling thread only, which takes part in the loop.
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<std::uint64_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines, 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        Worker& worker = integrand_.workers.local();
                        for (std::size_t l = range.begin(); l < range.end(); ++l) {
                          const KronrodPiece& piece = pieces[fresh[l / m]];
                          const double s = kronrodAbscissa(pair_, piece, int(l % m));
                          linePoints[l] =
                              integrateLine(worker, s, innerTolerance, cap, lineResult[l]);
                          done += linePoints[l];
                          if (std::this_thread::get_id() == caller) integrand_.report(points_ + done);
                        }
                      });
    for (std::uint64_t n : linePoints) points_ += n;
    std::vector<double> samples(values_ * m);
    for (std::size_t f = 0; f < fresh.size(); ++f) {
      KronrodPiece& piece = pieces[fresh[f]];
      for (int j = 0; j < pair_.points(); ++j) {
        const KronrodPiece& line = lineResult[f * m + std::size_t(j)];
        std::copy(line.value.begin(), line.value.end(), samples.begin() + std::ptrdiff_t(j) * std::ptrdiff_t(values_));
      }
      foldPiece(pair_, samples.data(), values_, piece);
      // The inner errors, integrated with the Kronrod weights, add to the piece's.
      const double half = 0.5 * (piece.b - piece.a);
      for (int j = 0; j < pair_.points(); ++j) {
        const KronrodPiece& line = lineResult[f * m + std::size_t(j)];
        for (std::size_t v = 0; v < values_; ++v) {
          piece.error[v] += half * pair_.kronrodWeight(j) * line.error[v];
        }
      }
      piece.worst = largestAbs(piece.error);
    }
  }

  // g(s) and its error into `line` (value, error); returns the points taken.
  std::uint64_t integrateLine(Worker& worker, double s, double tolerance, std::uint64_t cap,
                              KronrodPiece& line) const {
    std::vector<KronrodPiece> pieces = piecesBetween(lineBreaks(s));
    std::uint64_t points = 0;
    for (KronrodPiece& piece : pieces) points += evaluateInner(worker, s, piece);
    for (;;) {
      sumPieces(pieces, values_, line.value, line.error);
      if (largestAbs(line.error) <= tolerance || points >= cap) return points;
      if (!halveWorst(pieces, [&](std::vector<KronrodPiece>& next, const std::vector<std::size_t>& at) {
            for (std::size_t k : at) {
              points += evaluateInner(worker, s, next[k]);
              points += evaluateInner(worker, s, next[k + 1]);
            }
          })) {
        return points;
      }
    }
  }

  std::uint64_t evaluateInner(Worker& worker, double s, KronrodPiece& piece) const {
    std::vector<double>& samples = worker.samples;
    samples.resize(values_ * std::size_t(pair_.points()));
    for (int j = 0; j < pair_.points(); ++j) {
      integrand_.evaluate(worker, s, kronrodAbscissa(pair_, piece, j),
                          samples.data() + std::size_t(j) * values_);
    }
    foldPiece(pair_, samples.data(), values_, piece);
    return std::uint64_t(pair_.points());
  }

  OuterIntegrand& integrand_;
  const GaussKronrodPair& pair_;
  std::vector<ReceiverSegment> segments_;
  ExactGoldOptions options_;
  int grid_;
  std::size_t values_;
  std::vector<KronrodPiece> initial_;
  std::uint64_t points_ = 0;
  std::vector<double> baseline_;
  double share_ = 1.0;
};

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
  const double share = free ? kRestShare : 1.0;
  // Genz-Malik's own estimate (its embedded degree-5 rule) cannot see what no point of a
  // region samples, such as a thin shadow between its points: started from the whole square,
  // a run at the study's 3e-4 stopped early on 1 of 24 of the study's partial links at each
  // degree with an actual error 2.4 (degree 0) and 1.4 (degree 2) times its estimate
  // (tests/reference/gold_honesty_test.cpp, against critical-line golds at 1e-7). Started
  // from 8 x 8 regions (1,088 points), none failed, the worst actual error 0.16 and 0.33 of
  // the estimate; 4 x 4 and 2 x 2 passed too on those links, and 8 x 8 costs about as many
  // points as they do at 3e-4 (2,300 and 3,500 a link on average, against 1,800 and 3,400).
  auto genzMalik = [&] {
    GenzMalikOptions genz;
    genz.tolerance = share * options.tolerance;
    genz.initialGrid = options.initialGrid;
    genz.maxEvaluations = options.maxEvaluations;
    if (free) genz.baseline = free->value;
    const GenzMalikResult run = genzMalik2d(
        values,
        [&](std::size_t count, const double* points, double* out) {
          evaluateBatch(integrand, count, points, out);
        },
        genz);
    value = run.value;
    error = run.error;
  };
  ExactOuterMethod method = options.outer;
  const std::vector<ReceiverSegment> contact = contactSegments(link.receiver, candidates);
  if (method == ExactOuterMethod::criticalLines) {
    std::vector<ReceiverSegment> segments = criticalSegments(link.receiver, link.source, candidates);
    gold.criticalSegments = segments.size();
    CriticalLineCubature cubature(integrand, std::move(segments), options);
    if (free) cubature.setBaseline(free->value, share);
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
      integrand.points = cubature.points();
    } else {
      // Too many segments for their breakpoints. Where the inner integral jumps, Genz-Malik's
      // estimate is not to be trusted: a region's 17 points see a jump only as a difference
      // between them, and across the study's links its actual error reached 1.2 (degree 0)
      // and 5.3 (degree 2) times its estimate on a link with an occluder standing on the
      // receiver (the jump lines, below, met theirs). The jumps alone then stay breakpoints.
      method = contact.empty() ? ExactOuterMethod::genzMalik : ExactOuterMethod::jumpLines;
    }
  }
  if (method == ExactOuterMethod::jumpLines) {
    CriticalLineCubature cubature(integrand, contact, options, options.initialGrid);
    if (free) cubature.setBaseline(free->value, share);
    cubature.run(value, error);
    integrand.points = cubature.points();
  }
  if (method == ExactOuterMethod::genzMalik) genzMalik();
  if (!integrand.finite()) throw ComputationError("exact gold: the inner integral was not finite");
  if (free) {
    // K_free's error must fit the tolerance's remaining share of the whole's largest entry;
    // where the shadows take most of K, it was computed too loosely: higher orders.
    const double allowed = (1.0 - share) * options.tolerance * largestOfSum(free->value, value);
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
  gold.formFactor = gold.coupling(0, 0) * toFormFactor;
  gold.formFactorError = gold.couplingError(0, 0) * toFormFactor;
  const double largest = gold.coupling.cwiseAbs().maxCoeff();
  gold.converged = gold.couplingError.maxCoeff() <= options.tolerance * largest;
  gold.receiverPoints = integrand.points;
  // Every worker culled the same shaft: read the count from one instead of culling again.
  for (const Worker& worker : integrand.workers) {
    gold.polygonUnions += worker.visibility.statistics().unions;
    gold.candidateOccluders = worker.visibility.candidateCount();
  }
  return gold;
}

}  // namespace radquad
