// The exact-visibility gold (docs/design.md, "The gold"): a deterministic coupling of
// any link, occluded or not, with an estimate of its absolute error.
//
//   K[a][b] = sqrt(A_r / A_s) int_{[0,1]^2} phi_a(s, t) I_b(x(s, t)) ds dt,
//
// the inner integral I_b (source_moments.h) over the exactly visible part of the source
// (exact_visibility.h). I_b is analytic in x except on the critical segments of the receiver
// (critical_segments.h: where a shadow vertex crosses an edge, a source vertex enters a
// shadow, or x crosses the source's plane) and on the curves of three-edge events. The outer
// integral over the receiver's unit square is taken by one of two methods:
//   - critical lines (default): iterated adaptive Gauss-Kronrod (7, 15) (gauss_kronrod.h),
//     along t on lines s = const with breakpoints where the line crosses a segment, and over
//     s with breakpoints at the segments' ends; each line's integral to a share (innerShare)
//     of the tolerance, the outer pieces halved where the Kronrod-Gauss differences (plus the
//     lines' own errors) are largest. Between breakpoints the integrands are analytic, so the
//     rules converge exponentially and the breakpoints alone usually suffice. The breakpoints'
//     grid costs 15 x 15 points per cell (about the square of the segments' count): when
//     that floor exceeds maxFloorPoints, the link takes
//   - jump lines, when the inner integral jumps somewhere on the receiver (an occluder meets
//     it: contactSegments): the same lines with only the jumps as breakpoints, each line and
//     the outer integral starting from initialGrid equal pieces; the kinks are left to the
//     halving. Genz-Malik's estimate misjudges jumps (exact_gold.cpp);
//   - Genz-Malik otherwise: the degree-7 rule with its embedded degree-5 rule as the error
//     estimate (genz_malik.h), from a grid of initialGrid^2 regions, bisecting the regions of
//     largest error; blind to the segments, it resolves them algebraically.
// At degree >= 1, when the receiver lies in front of the source's plane (unoccludedApart), K
// is split as K_free + K_rest: K_free, the inner integrals over S' alone (the same polygon from
// every receiver point, an analytic integrand), by Gauss-Legendre products of rising order;
// K_rest, over minus the shadows' union alone, by the method above to 0.9 of the tolerance,
// K_free's error held to the rest.
// Both stop when the estimated error of every coefficient is at most `tolerance` times K's
// largest entry, or when the evaluation budget is spent (then converged = false). No random
// numbers: the same link gives the same bits, whatever the number of threads (lines, or the
// points of a batch, are spread over threads; each value depends on its point only).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "kernel/coupling.h"

namespace radquad {

// The outer (receiver) integral: Gauss-Kronrod along lines with the critical segments as
// breakpoints (critical_segments.h; the default, which falls back to one of the other two
// where the breakpoints are too many), Gauss-Kronrod along lines with only the jumps as
// breakpoints (contactSegments) over a grid of initialGrid pieces each way, or Genz-Malik
// cubature over the square, blind to where the integrand has kinks.
enum class ExactOuterMethod { criticalLines, jumpLines, genzMalik };

struct ExactGoldOptions {
  double tolerance = 1e-7;             // estimated error / max |K| entry
  // The budget of receiver points (each an exact inner integral).
  std::size_t maxEvaluations = 4000000;
  // Genz-Malik starts from a grid of initialGrid x initialGrid regions (genz_malik.h): no
  // part of the square is judged from fewer points, so a shadow thinner than the space
  // between a large region's points is not missed (exact_gold.cpp says how 8 was chosen).
  int initialGrid = 8;
  // Below this tolerance a Genz-Malik run is confirmed by a second one (exact_gold.cpp): its
  // estimate alone was measured to miss coherent errors at tight tolerances.
  double confirmBelow = 1e-4;
  ExactOuterMethod outer = ExactOuterMethod::criticalLines;
  // Critical lines: the share of the tolerance left to the inner (t) integrals, and the
  // receiver points one line may take.
  double innerShare = 0.1;
  // The Gauss-Kronrod pair of the critical lines: 7 (the (3, 7) pair), 15 (the (7, 15) pair),
  // or 0: 15 below a tolerance of 1e-6, 7 from there on.
  int kronrodPoints = 0;
  std::size_t maxLinePoints = 20000;
  // Critical lines only when the breakpoints alone take at most this many receiver points
  // (the pair's points squared per cell of the breakpoints' grid) at tolerance 1e-7, scaled
  // by (1e-7 / tolerance)^(1/2) (Genz-Malik's points grow so, the floor does not); Genz-Malik
  // otherwise. Measured on the study's links (bench/gold_bench.cpp): at degree 0 and 1e-7,
  // Genz-Malik needs about as many points as the floor from 30,000 on; at degree >= 1 it
  // needs 2 to 4 times more than at degree 0, the critical lines the same.
  std::uint64_t maxFloorPoints = 30000;
  std::uint64_t maxFloorPointsHigherDegrees = 120000;
  // Degree >= 1, occluders in the shaft, the receiver in front of the source's plane: the
  // unoccluded part of K (the inner integrals over S' alone, an analytic integrand) by its own
  // Genz-Malik run, and the outer integration above over minus the shadows' union alone.
  // Each receiver point then integrates the shadows' edges only, not S''s as well.
  bool unoccludedApart = true;
  // Called from the calling thread about once a second once the gold has run a second
  // (receiver points so far, seconds); may be empty.
  std::function<void(std::uint64_t points, double seconds)> progress;
};

struct ExactGold {
  Eigen::MatrixXd coupling;
  Eigen::MatrixXd couplingError;  // estimated absolute error of every entry
  double formFactor = 0.0;
  double formFactorError = 0.0;
  bool converged = false;
  // Genz-Malik below confirmBelow: its two runs agreed within their summed estimates (true
  // where no confirmation is asked for). A gold that is not confirmed is not converged.
  bool confirmed = true;
  std::uint64_t receiverPoints = 0;   // outer evaluations: receiver points computed
  std::uint64_t polygonUnions = 0;    // receiver points whose shadows overlapped
  std::size_t candidateOccluders = 0;  // occluder polygons in the link's shaft
  std::size_t criticalSegments = 0;    // critical lines: segments on the receiver
  ExactOuterMethod outer = ExactOuterMethod::criticalLines;  // the method used
  bool unoccludedApart = false;  // the unoccluded part was integrated apart (its points counted)
};

// "critical lines", "jump lines" or "genz-malik".
const char* exactOuterMethodName(ExactOuterMethod method);

ExactGold exactGold(const Link& link, int degree, const ExactGoldOptions& options = {});

}  // namespace radquad
