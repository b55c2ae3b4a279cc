// The pieces of a 1D adaptive Gauss-Kronrod integration of a vector of functions (the exact
// gold's outer integral, critical_line_cubature.h): a piece's Kronrod value and its error estimate,
// the pieces between breakpoints, the halving of the worst pieces, and their sum.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "reference/gauss_kronrod.h"

namespace radquad {

// One piece [a, b] of [0, 1] with the integrals of every function over it.
struct KronrodPiece {
  double a = 0.0, b = 0.0;
  std::vector<double> value, error;  // Kronrod estimate; |Kronrod - Gauss| (+ inner errors)
  double worst = 0.0;                // the largest entry of error
};

double largestAbs(const std::vector<double>& v);

// Folds the samples of a piece (samples[j * values + v] at the pair's point j) into
// its value and error: the Kronrod sum, and its distance from the embedded Gauss sum (the
// Gauss rule's error, a bound on the Kronrod rule's, which is far smaller on analytic pieces).
void foldPiece(const GaussKronrodPair& pair, const double* samples, std::size_t values,
               KronrodPiece& piece);

// The abscissa of the pair's point j on the piece.
double kronrodAbscissa(const GaussKronrodPair& pair, const KronrodPiece& piece, int j);

// The pieces between sorted breakpoints in [0, 1] (gaps under 1e-12 merged).
std::vector<KronrodPiece> piecesBetween(std::vector<double> breaks);

// One round of the global adaptive strategy: the pieces carrying at least a quarter of the
// largest piece error are halved (several at once, so that an outer round's lines run in
// parallel), and evaluate(pieces, indices of the new halves' first pieces) fills them.
// Returns false when no piece can be halved.
template <class Evaluate>
bool halveWorst(std::vector<KronrodPiece>& pieces, Evaluate&& evaluate) {
  double largest = 0.0;
  for (const KronrodPiece& piece : pieces) largest = std::max(largest, piece.worst);
  std::vector<KronrodPiece> next;
  std::vector<std::size_t> at;
  for (const KronrodPiece& piece : pieces) {
    if (piece.worst > 0.0 && piece.worst >= 0.25 * largest && piece.b - piece.a > 1e-12) {
      const double middle = 0.5 * (piece.a + piece.b);
      at.push_back(next.size());
      next.push_back(KronrodPiece{piece.a, middle, {}, {}, 0.0});
      next.push_back(KronrodPiece{middle, piece.b, {}, {}, 0.0});
    } else {
      next.push_back(piece);
    }
  }
  if (at.empty()) return false;
  evaluate(next, at);
  pieces = std::move(next);
  return true;
}

// The sums of the pieces' values and errors.
void sumPieces(const std::vector<KronrodPiece>& pieces, std::size_t values,
               std::vector<double>& value, std::vector<double>& error);

}  // namespace radquad
