#include "reference/adaptive_pieces.h"

#include <algorithm>
#include <cmath>

namespace radquad {

double largestAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

void foldPiece(const GaussKronrodPair& pair, const double* samples, std::size_t values,
               KronrodPiece& piece) {
  piece.value.assign(values, 0.0);
  std::vector<double> gauss(values, 0.0);
  const double half = 0.5 * (piece.b - piece.a);
  for (int j = 0; j < pair.points(); ++j) {
    const double kronrod = half * pair.kronrodWeight(j);
    const double gaussWeight = half * pair.gaussWeight(j);
    for (std::size_t v = 0; v < values; ++v) {
      piece.value[v] += kronrod * samples[std::size_t(j) * values + v];
      gauss[v] += gaussWeight * samples[std::size_t(j) * values + v];
    }
  }
  piece.error.resize(values);
  for (std::size_t v = 0; v < values; ++v) piece.error[v] = std::abs(piece.value[v] - gauss[v]);
  piece.worst = largestAbs(piece.error);
}

double kronrodAbscissa(const GaussKronrodPair& pair, const KronrodPiece& piece, int j) {
  return 0.5 * (piece.a + piece.b) + 0.5 * (piece.b - piece.a) * pair.node(j);
}

std::vector<KronrodPiece> piecesBetween(std::vector<double> breaks) {
  std::sort(breaks.begin(), breaks.end());
  std::vector<KronrodPiece> pieces;
  double start = 0.0;
  for (double b : breaks) {
    b = std::min(std::max(b, 0.0), 1.0);
    if (b - start > 1e-12) {
      pieces.push_back(KronrodPiece{start, b, {}, {}, 0.0});
      start = b;
    }
  }
  if (pieces.empty()) pieces.push_back(KronrodPiece{0.0, 1.0, {}, {}, 0.0});
  pieces.back().b = 1.0;
  return pieces;
}

void sumPieces(const std::vector<KronrodPiece>& pieces, std::size_t values,
               std::vector<double>& value, std::vector<double>& error) {
  value.assign(values, 0.0);
  error.assign(values, 0.0);
  for (const KronrodPiece& piece : pieces) {
    for (std::size_t v = 0; v < values; ++v) {
      value[v] += piece.value[v];
      error[v] += piece.error[v];
    }
  }
}

}  // namespace radquad
