// Integration of one link's coupling K (docs/design.md) with a Gauss product rule
// {Rs, Rt, Su, Sv}, with a subdivision near the kernel's singularity.
//
// Where two elements touch (a shared edge or corner, a block standing on a floor), the
// kernel 1/r^2 is unbounded and a product rule over the whole pair converges only like the
// size of the touching region: a 1-point rule on two unit squares sharing an edge gives
// F = 1/pi instead of 0.2000. Such a pair is split into pieces, recursively where the pieces
// are still near (elementsNear), and the link's rule is applied on every piece with the
// elements' own basis functions evaluated at the piece's points: a composite product rule for
// the whole pair. Likewise where one element crosses the other's plane (cutByTangentPlane):
// the clamped cosine makes the kernel discontinuous there, and a product rule over the pair
// converges slowly (a one-point rule on a source whose centre lies behind the receiver's
// plane sees nothing of its front part), so the elements that straddle the other's plane are
// quartered, to `depth` levels, where they still straddle it; pieces wholly behind are
// dropped. Near pieces: a piece no longer than twice its width is split into its 4 quadrants (one
// level of `depth`); a longer one is first halved across its long side, at no cost in depth,
// so every piece that reaches the singularity is nearly square. (Quadrants of a 40:1 strip
// stay 40:1: along a shared long edge the kernel's peak, as wide as the strips, falls between
// the rule's points and the coupling grows like length over width, far above any physical
// form factor.) The composite rule equals putting the pieces' own couplings together with the
// two-scale matrices, K_parent = sum_{c, c'} T_c^T K_(c, c') T_c' (radiosity/two_scale.h), since
// a parent function restricted to a piece is exactly a combination of the piece's functions;
// it skips the (F x F)^2 products of that assembly, which would cost more than the kernel
// evaluations of a small adaptive rule.
#pragma once

#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

#include "kernel/coupling.h"
#include "quadrature/gauss_legendre.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/visibility.h"

namespace radquad {

// Whether a corner of either parallelogram lies on the other (within a relative tolerance).
bool elementsTouch(const Patch& a, const Patch& b);

// Elements whose centres are closer than kNearFactor times the sum of their radii, or that
// touch: there the kernel varies too fast for a product rule over the whole pair.
inline constexpr double kNearFactor = 1.0;
bool elementsNear(const Patch& a, const Patch& b);

// What integrating one link adds to the solver's counts.
struct LinkIntegrationCounts {
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t raysCast = 0;
};

// Integrates links with Gauss product rules; one per thread (it keeps scratch space, so a
// warm integrator allocates nothing beyond the output's first sizing).
class LinkIntegrator {
 public:
  // Writes the link's coupling (rows receiver, columns source functions) for `rule`
  // {Rs, Rt, Su, Sv} from `tables`, splitting touching pairs up to `depth` levels.
  LinkIntegrationCounts integrate(const Link& link, const GaussPointCounts& rule,
                                  const GaussTables& tables, int depth,
                                  Eigen::Map<Eigen::MatrixXd> coupling) {
    return integrate(link, rule, tables, depth, composite(link.receiver, link.source, depth),
                     coupling);
  }
  // The same for a caller that has already asked composite() (the solver sizes its store by
  // the answer).
  LinkIntegrationCounts integrate(const Link& link, const GaussPointCounts& rule,
                                  const GaussTables& tables, int depth, bool isComposite,
                                  Eigen::Map<Eigen::MatrixXd> coupling);

  // Whether integrate uses the pieces' composite rule for these elements at this depth.
  static bool composite(const Patch& receiver, const Patch& source, int depth) {
    return depth > 0 && (elementsNear(receiver, source) || cutByTangentPlane(receiver, source));
  }

 private:
  // A rectangle [u0, u0 + du] x [v0, v0 + dv] of an element's parameter square.
  struct Square {
    double u0 = 0.0, v0 = 0.0, du = 1.0, dv = 1.0;
    // Orders and groups the pieces by receiver rectangle: larger ones first.
    std::tuple<double, double, double, double> key() const { return {du * dv, du, u0, v0}; }
  };
  struct Piece {
    Square receiver, source;
  };
  // Appends the pieces of the pair (rectangles of the link's elements, whose geometry is
  // `receiver` and `source`): the pair itself, or, where the two are near, the pieces of
  // the pairs of their halves (long pieces) or quadrants (the others; one level of depth).
  void collectPieces(const Patch& receiverElement, const Square& receiverSquare,
                     const Patch& sourceElement, const Square& sourceSquare, int depth);
  // Writes `side`'s points mapped into `square` to points offset .. offset + side's count of
  // `placed` (sized to `total` points), with weights scaled by the rectangle's area and the
  // element's basis values there.
  static void placeSide(const GaussSide& side, int pointsU, int pointsV, const Square& square,
                        GaussSide& placed, std::size_t offset, std::size_t total);

  CouplingAccumulator accumulator_;
  LinkIntegral piece_;
  GaussSide receiverPiece_, sourcePiece_;
  std::vector<Piece> pieces_;
};

}  // namespace radquad
