// Integration of one link's coupling K (DESIGN.md) with a Gauss product rule
// {Rs, Rt, Su, Sv}, with a subdivision near the kernel's singularity.
//
// Where two elements touch (a shared edge or corner, a block standing on a floor), the
// kernel 1/r^2 is unbounded and a product rule over the whole pair converges only like the
// size of the touching region: a 1-point rule on two unit squares sharing an edge gives
// F = 1/pi instead of 0.2000. Such a pair is split into its 4 x 4 quadrant pairs, recursively
// up to `depth` levels where the quadrants still touch, and the link's rule is applied on
// every piece with the elements' own basis functions evaluated at the piece's points: a
// composite product rule for the whole pair. It equals putting the pieces' own couplings
// together with the two-scale matrices, K_parent = sum_{c, c'} T_c^T K_(c, c') T_c'
// (radiosity/two_scale.h), since a parent function restricted to a quadrant is exactly that
// combination of the quadrant's functions; it skips the (F x F)^2 products of that assembly,
// which would cost more than the kernel evaluations of a small adaptive rule.
#pragma once

#include <array>
#include <cstdint>
#include <tuple>
#include <vector>

#include "kernel/coupling.h"
#include "radiosity/gauss_tables.h"

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
  LinkIntegrationCounts integrate(const Link& link, const std::array<int, 4>& rule,
                                  const GaussTables& tables, int depth,
                                  Eigen::Map<Eigen::MatrixXd> coupling);

  // Whether integrate uses the pieces' composite rule for these elements at this depth.
  static bool composite(const Patch& receiver, const Patch& source, int depth) {
    return depth > 0 && elementsNear(receiver, source);
  }

 private:
  // A square [u0, u0 + size] x [v0, v0 + size] of an element's parameter square.
  struct Square {
    double u0 = 0.0, v0 = 0.0, size = 1.0;
    // Orders and groups the pieces by receiver square: larger squares first.
    std::tuple<double, double, double> key() const { return {size, u0, v0}; }
  };
  struct Piece {
    Square receiver, source;
  };
  // Appends the pieces of the pair (squares of the link's elements): the pair itself, or,
  // where the two still touch and depth > 0, the pieces of its quadrant pairs.
  void collectPieces(const Patch& receiver, const Square& receiverSquare, const Patch& source,
                     const Square& sourceSquare, int depth);
  // Writes `side`'s points mapped into `square` to points offset .. offset + side's count of
  // `placed` (sized to `total` points), with weights scaled by the square's area and the
  // element's basis values there.
  static void placeSide(const GaussSide& side, int pointsU, int pointsV, const Square& square,
                        GaussSide& placed, std::size_t offset, std::size_t total);

  CouplingAccumulator accumulator_;
  LinkIntegral piece_;
  GaussSide receiverPiece_, sourcePiece_;
  std::vector<Piece> pieces_;
};

}  // namespace radquad
