// The exact gold's critical lines (exact_gold.h): the outer integral as iterated adaptive
// Gauss-Kronrod with the critical segments as breakpoints. Internal to the exact gold.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "reference/adaptive_pieces.h"
#include "reference/critical_segments.h"
#include "reference/exact_gold.h"
#include "reference/gauss_kronrod.h"
#include "reference/outer_integrand.h"

namespace radquad::exact_gold_detail {

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

}  // namespace radquad::exact_gold_detail
