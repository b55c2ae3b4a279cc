#include "reference/exact_gold.h"

#include <cubature.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <functional>
#include <thread>
#include <unordered_map>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"
#include "kernel/progress_throttle.h"
#include "quadrature/gauss_legendre.h"
#include "reference/critical_segments.h"
#include "reference/exact_visibility.h"
#include "reference/adaptive_pieces.h"
#include "reference/gauss_kronrod.h"
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

// The inner integrals of the points a Genz-Malik run computed, for the runs that repeat it at
// a quarter of its tolerance: a repeat starts again from the whole square and halves its
// regions the same way, so most of the points it asks for are the earlier runs' points, to
// the last bit. Their inner integrals are looked up instead of computed again, and they are
// the same either way (a point's inner integrals depend on the point alone, not on the
// thread or on the points before it). At most `capacity` points are kept (their storage
// taken at once): the runs that are repeated took fewer than minEvaluations points each.
class PointCache {
 public:
  PointCache(std::size_t capacity, int functions)
      : capacity_(capacity), functions_(std::size_t(functions)) {
    index_.reserve(capacity);
    stored_.reserve(capacity * functions_);
  }

  // The stored inner integrals of (s, t), or nullptr.
  const double* find(double s, double t) const {
    if (capacity_ == 0) return nullptr;
    const auto it = index_.find(keyOf(s, t));
    return it == index_.end() ? nullptr : stored_.data() + it->second;
  }

  void add(double s, double t, const double* inner) {
    if (index_.size() >= capacity_) return;
    if (!index_.emplace(keyOf(s, t), stored_.size()).second) return;
    stored_.insert(stored_.end(), inner, inner + functions_);
  }

 private:
  struct Key {
    std::uint64_t s, t;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    std::size_t operator()(const Key& key) const {
      return std::hash<std::uint64_t>()(key.s * 0x9E3779B97F4A7C15ull ^ key.t);
    }
  };
  static Key keyOf(double s, double t) {
    return {std::bit_cast<std::uint64_t>(s), std::bit_cast<std::uint64_t>(t)};
  }
  std::size_t capacity_;
  std::size_t functions_;
  std::unordered_map<Key, std::size_t, Hash> index_;
  std::vector<double> stored_;
};

struct CallbackData {
  OuterIntegrand* integrand;
  PointCache* cache;
  std::uint64_t requested = 0;        // the points asked for, those found in the cache included
  std::vector<std::size_t> fresh;     // scratch: the batch's points not in the cache
  std::vector<double> inner;          // scratch: their inner integrals
  std::vector<double> receiverValues; // scratch: the receiver's functions at a point
};

// Points are independent: a batch is spread over threads, and the values do not depend on
// which thread computed them.
int integrandCallback(unsigned /*dimensions*/, std::size_t count, const double* points, void* data,
                      unsigned values, double* out) {
  auto& call = *static_cast<CallbackData*>(data);
  OuterIntegrand* integrand = call.integrand;
  const std::size_t functions = std::size_t(integrand->functions);
  std::vector<std::size_t>& fresh = call.fresh;
  fresh.clear();
  call.requested += count;
  call.receiverValues.resize(functions);
  for (std::size_t k = 0; k < count; ++k) {
    const double s = points[2 * k], t = points[2 * k + 1];
    if (const double* known = call.cache->find(s, t)) {
      integrand->expand(call.receiverValues.data(), s, t, known, out + k * values);
    } else {
      fresh.push_back(k);
    }
  }
  integrand->points += fresh.size();
  integrand->report(integrand->points);
  call.inner.resize(fresh.size() * functions);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fresh.size(), 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Worker& worker = integrand->workers.local();
                      for (std::size_t f = range.begin(); f < range.end(); ++f) {
                        const std::size_t k = fresh[f];
                        integrand->evaluate(worker, points[2 * k], points[2 * k + 1],
                                            out + k * values, call.inner.data() + f * functions);
                      }
                    });
  for (std::size_t f = 0; f < fresh.size(); ++f) {
    const std::size_t k = fresh[f];
    call.cache->add(points[2 * k], points[2 * k + 1], call.inner.data() + f * functions);
  }
  return integrand->finite() ? 0 : 1;
}

// The outer integral as iterated adaptive Gauss-Kronrod (gauss_kronrod.h) with the critical segments
// (critical_segments.h) as breakpoints: g(s) = int_0^1 f(s, t) dt along each line s = const,
// the breakpoints where the line crosses a segment; the outer integral of g over s, the
// breakpoints at the segments' ends and at segments along t. Between them the integrands are
// analytic (but for the three-edge events), and Gauss-Kronrod converges exponentially.
class CriticalLineCubature {
 public:
  CriticalLineCubature(OuterIntegrand& integrand, std::vector<ReceiverSegment> segments,
                       const ExactGoldOptions& options)
      : integrand_(integrand),
        pair_(options.kronrodPoints == 15 ||
                      (options.kronrodPoints == 0 && options.tolerance < 1e-6)
                  ? GaussKronrodPair::fifteenPoint()
                  : GaussKronrodPair::sevenPoint()),
        segments_(std::move(segments)),
        options_(options),
        values_(std::size_t(integrand.functions * integrand.functions)) {
    std::vector<double> breaks = {0.0, 1.0};
    for (const auto& segment : segments_) {
      breaks.push_back(segment.a.x());
      breaks.push_back(segment.b.x());
    }
    initial_ = piecesBetween(std::move(breaks));
  }

  // Receiver points the initial breakpoints alone take (no bisection): the cost floor.
  std::uint64_t floorPoints() const {
    std::uint64_t points = 0;
    for (const KronrodPiece& piece : initial_) {
      const std::size_t pieces = piecesBetween(crossingsAt(segments_, 0.5 * (piece.a + piece.b))).size();
      points += std::uint64_t(pair_.points()) * std::uint64_t(pair_.points()) * pieces;
    }
    return points;
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
    evaluateOuter(pieces, all, options_.innerShare * options_.tolerance * scale);
    for (;;) {
      sumPieces(pieces, values_, value, error);
      scale = largestAbs(value);
      const double target = options_.tolerance * scale;
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
  double estimateScale() {
    const GaussLegendreRule& rule = gaussLegendreUnit(16);
    const std::size_t n = rule.nodes.size();
    std::vector<std::vector<double>> rows(n, std::vector<double>(values_, 0.0));
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      Worker& worker = integrand_.workers.local();
      std::vector<double> sample(values_);
      for (std::size_t j = 0; j < n; ++j) {
        integrand_.evaluate(worker, rule.nodes[i], rule.nodes[j], sample.data());
        for (std::size_t v = 0; v < values_; ++v) {
          rows[i][v] += rule.weights[i] * rule.weights[j] * sample[v];
        }
      }
    });
    points_ += n * n;
    std::vector<double> total(values_, 0.0);
    for (const auto& row : rows) {
      for (std::size_t v = 0; v < values_; ++v) total[v] += row[v];
    }
    return largestAbs(total);
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
    std::vector<KronrodPiece> pieces = piecesBetween(crossingsAt(segments_, s));
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
  std::size_t values_;
  std::vector<KronrodPiece> initial_;
  std::uint64_t points_ = 0;
};

}  // namespace

const char* exactOuterMethodName(ExactOuterMethod method) {
  return method == ExactOuterMethod::criticalLines ? "critical lines" : "genz-malik";
}

ExactGold exactGold(const Link& link, int degree, const ExactGoldOptions& options) {
  validateBasisDegree(degree);
  if (!(options.tolerance > 0.0)) throw InputError("exact gold: tolerance must be positive");
  OuterIntegrand integrand(link, degree, options.tolerance);
  integrand.progress = options.progress;
  const unsigned values = unsigned(integrand.functions * integrand.functions);
  std::vector<double> value(values), error(values);
  ExactGold gold;
  std::uint64_t requestedPoints = 0;
  auto genzMalik = [&] {
    // Genz-Malik's estimate (its embedded degree-5 rule) can miss what a run of few regions
    // never samples, a thin shadow between its points: at a tolerance of 1e-4, 4 of 84 of the
    // study's occluded links stopped after 17 to 800 points with an actual error 2 to 40
    // times the estimate (against 1e-8 golds). A run that stops before minEvaluations points
    // is repeated at a quarter of its tolerance (at most 5 times, and only while the budget
    // left holds minEvaluations points); the last run that met its tolerance is the result.
    // (The retries sample more regions; the inner integrals keep the accuracy the requested
    // tolerance asked for, a hundredth of it.)
    // The rounds and the budget count the points the runs asked for, repeats included (as
    // many as they would compute without the cache); integrand.points, those computed.
    double tolerance = options.tolerance;
    std::vector<double> runValue(values), runError(values);
    PointCache cache(options.reuseRepeatedPoints ? 2 * options.minEvaluations : 0,
                     integrand.functions);
    CallbackData call{&integrand, &cache, 0, {}, {}, {}};
    for (int round = 0;; ++round) {
      const std::uint64_t before = call.requested;
      const double low[2] = {0.0, 0.0}, high[2] = {1.0, 1.0};
      // hcubature may overshoot its budget by a region's points: what is left is never
      // allowed to wrap around (a repeat starts only while minEvaluations are left).
      const int status = hcubature_v(values, integrandCallback, &call, 2, low, high,
                                     options.maxEvaluations - before, 0.0, tolerance, ERROR_LINF,
                                     runValue.data(), runError.data());
      if (!integrand.finite()) {
        throw ComputationError("exact gold: the inner integral was not finite");
      }
      if (status != 0) throw ComputationError("exact gold: the cubature failed");
      double largestValue = 0.0, largestError = 0.0;
      for (unsigned v = 0; v < values; ++v) {
        largestValue = std::max(largestValue, std::abs(runValue[v]));
        largestError = std::max(largestError, runError[v]);
      }
      const bool met = largestError <= tolerance * largestValue;
      if (round == 0 || met) {
        value = runValue;
        error = runError;
      }
      if (!met || call.requested - before >= options.minEvaluations || round == 5 ||
          call.requested + options.minEvaluations > options.maxEvaluations) {
        break;
      }
      tolerance *= 0.25;
    }
    requestedPoints = call.requested;
  };
  bool lines = options.outer == ExactOuterMethod::criticalLines;
  if (lines) {
    // The shaft's occluders as one worker culled them (instead of culling once more).
    std::vector<ReceiverSegment> segments = criticalSegments(
        link.receiver, link.source, integrand.workers.local().visibility.candidates());
    gold.criticalSegments = segments.size();
    CriticalLineCubature cubature(integrand, std::move(segments), options);
    // Many segments make the breakpoints' product costly (floor ~ segments^2): then the
    // bisection of Genz-Malik, linear in the segments' length, is cheaper.
    // Genz-Malik's points grow as tolerance^(-1/2), the floor not at all: the threshold
    // scales so.
    const double threshold =
        double(degree == 0 ? options.maxFloorPoints : options.maxFloorPointsHigherDegrees) *
        std::sqrt(1e-7 / options.tolerance);
    lines = double(cubature.floorPoints()) <= threshold;
    if (lines) {
      cubature.run(value, error);
      integrand.points = cubature.points();
      requestedPoints = integrand.points;
      if (!integrand.finite()) {
        throw ComputationError("exact gold: the inner integral was not finite");
      }
    }
  }
  if (!lines) genzMalik();
  gold.outer = lines ? ExactOuterMethod::criticalLines : ExactOuterMethod::genzMalik;
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
  gold.requestedPoints = requestedPoints;
  // Every worker culled the same shaft: read the count from one instead of culling again.
  for (const Worker& worker : integrand.workers) {
    gold.polygonUnions += worker.visibility.statistics().unions;
    gold.candidateOccluders = worker.visibility.candidateCount();
  }
  return gold;
}

}  // namespace radquad
