// The contraction of a product rule's kernel matrix with the two sides' weighted basis
// tables (kernel/coupling.cpp), one compiled function per basis degree; not part of the
// kernel's interface.
#pragma once

#include <cstddef>
#include <cstring>

#include "kernel/legendre_basis.h"
#include "kernel/simd_lanes.h"

namespace radquad::detail {

// Both orders below contract matrices with rows of F values (F = (d+1)^2 known at compile
// time). Each output element is a sum over k in increasing order,
//   out[r * F + c] = sum_k left[k * kStride + r] right[k * F + c],
// one multiply-add per term. A single such sum is a chain of dependent multiply-adds, so 8
// neighbouring rows r are accumulated together as one vector per column c (F independent
// chains); every blocking keeps the order of each sum, so the results do not depend on it.
// The vectors are GCC/Clang vector extensions: they compile to single AVX-512 instructions
// where available and to pairs or quadruples of narrower ones elsewhere.
// Scalar terms are fused explicitly: left to contraction, the compiler may group scalar
// products into vectors and round them before adding. Vector terms are always contracted.
using Lanes8 = simd::Doubles8;
constexpr int kLanes = simd::kLanes;

inline double multiplyAdd(double a, double b, double sum) {
#ifdef __FMA__
  return __builtin_fma(a, b, sum);
#else
  return a * b + sum;
#endif
}

// Rows r0..r0+7 of out, vectorised along r.
template <int F>
inline void contractEightRows(std::size_t n, const double* __restrict left, std::size_t kStride,
                              const double* __restrict right, double* __restrict out) {
  Lanes8 sum[F] = {};
  for (std::size_t k = 0; k < n; ++k) {
    Lanes8 scales;
    std::memcpy(&scales, left + k * kStride, sizeof scales);
    const double* __restrict row = right + k * F;
    for (int c = 0; c < F; ++c) sum[c] += scales * row[c];
  }
  for (int c = 0; c < F; ++c) {
    for (int r = 0; r < kLanes; ++r) out[std::size_t(r) * F + c] = sum[c][r];
  }
}

// Rows r = 0..Rows-1 of out[r * F + c] = sum_k left[k + r * rStride] right[k * F + c] (left's
// rows lie apart, right's rows are contiguous), vectorised along c: each row accumulates F / 8
// vectors and F % 8 scalars, Rows rows at once.
template <int F, int Rows>
inline void contractRowsAlongColumns(std::size_t n, const double* __restrict left,
                                     std::size_t rStride, const double* __restrict right,
                                     double* __restrict out) {
  constexpr int V = F / kLanes, S = F % kLanes;
  Lanes8 vectors[Rows][V > 0 ? V : 1] = {};
  double scalars[Rows][S > 0 ? S : 1] = {};
  for (std::size_t k = 0; k < n; ++k) {
    const double* __restrict row = right + k * F;
    Lanes8 values[V > 0 ? V : 1];
    for (int v = 0; v < V; ++v) std::memcpy(&values[v], row + v * kLanes, sizeof(Lanes8));
    for (int r = 0; r < Rows; ++r) {
      const double scale = left[k + std::size_t(r) * rStride];
      for (int v = 0; v < V; ++v) vectors[r][v] += scale * values[v];
      for (int c = 0; c < S; ++c) {
        scalars[r][c] = multiplyAdd(scale, row[V * kLanes + c], scalars[r][c]);
      }
    }
  }
  for (int r = 0; r < Rows; ++r) {
    double* __restrict target = out + std::size_t(r) * F;
    for (int v = 0; v < V; ++v) std::memcpy(target + v * kLanes, &vectors[r][v], sizeof(Lanes8));
    for (int c = 0; c < S; ++c) target[V * kLanes + c] = scalars[r][c];
  }
}

// Rows 0..count-1 of out[r * F + c] = sum_k left[k * kStride + r] right[k * F + c]: neighbouring
// rows r are neighbours in left, so eight of them make one vector.
template <int F>
inline void contractRows(std::size_t count, std::size_t n, const double* __restrict left,
                         std::size_t kStride, const double* __restrict right,
                         double* __restrict out) {
  const std::size_t blocked = count - count % kLanes;
  for (std::size_t r = 0; r < blocked; r += kLanes) {
    contractEightRows<F>(n, left + r, kStride, right, out + r * F);
  }
  for (std::size_t r = blocked; r < count; ++r) {
    // A lone row: its scales left[k * kStride + r] lie kStride apart.
    double sum[F] = {};
    for (std::size_t k = 0; k < n; ++k) {
      const double scale = left[k * kStride + r];
      for (int c = 0; c < F; ++c) sum[c] = multiplyAdd(scale, right[k * F + c], sum[c]);
    }
    for (int c = 0; c < F; ++c) out[r * F + c] = sum[c];
  }
}

// Rows 0..count-1 of out[r * F + c] = sum_k left[k + r * rStride] right[k * F + c], a few rows
// at a time.
template <int F>
inline void contractSpacedRows(std::size_t count, std::size_t n, const double* __restrict left,
                               std::size_t rStride, const double* __restrict right,
                               double* __restrict out) {
  constexpr int B = F <= 4 ? 8 : (F <= 16 ? 4 : 2);
  const std::size_t blocked = count - count % B;
  for (std::size_t r = 0; r < blocked; r += B) {
    contractRowsAlongColumns<F, B>(n, left + r * rStride, rStride, right, out + r * F);
  }
  for (std::size_t r = blocked; r < count; ++r) {
    contractRowsAlongColumns<F, 1>(n, left + r * rStride, rStride, right, out + r * F);
  }
}

// coupling (column-major F x F) = receiverBasis^T (nr x F) * (kernel (nr x ns) * sourceBasis
// (ns x F)): first each receiver point's row of the partial product, then each column of the
// coupling.
template <int F>
void contractProduct(std::size_t nr, std::size_t ns, const double* __restrict kernel,
                     const double* __restrict receiverBasis, const double* __restrict sourceBasis,
                     double* __restrict partial, double* __restrict coupling) {
  // partial[i * F + b] = sum_j kernel[i][j] sourceBasis[j][b].
  contractSpacedRows<F>(nr, ns, kernel, ns, sourceBasis, partial);
  // coupling[b * F + a] = sum_i partial[i][b] receiverBasis[i][a].
  contractRows<F>(F, nr, partial, F, receiverBasis, coupling);
}

// The same product in the other order, coupling = (receiverBasis^T kernel) sourceBasis:
// F nr ns + F ns F multiplications instead of nr ns F + F nr F, fewer when the source has
// fewer points than the receiver (the adaptive rules of Gershbein 1995, section 5).
template <int F>
void contractProductSourceLast(std::size_t nr, std::size_t ns, const double* __restrict kernel,
                               const double* __restrict receiverBasis,
                               const double* __restrict sourceBasis, double* __restrict partial,
                               double* __restrict coupling) {
  // partial[j * F + a] = sum_i kernel[i][j] receiverBasis[i][a].
  contractRows<F>(ns, nr, kernel, ns, receiverBasis, partial);
  // coupling[b * F + a] = sum_j sourceBasis[j][b] partial[j][a].
  contractRows<F>(F, ns, sourceBasis, F, partial, coupling);
}

using ContractFunction = void (*)(std::size_t, std::size_t, const double*, const double*,
                                  const double*, double*, double*);

// Indexed by basis degree d = 0..kMaxBasisDegree, F = (d+1)^2.
constexpr ContractFunction kContract[kMaxBasisDegree + 1] = {
    contractProduct<1>,  contractProduct<4>,  contractProduct<9>,
    contractProduct<16>, contractProduct<25>, contractProduct<36>,
    contractProduct<49>, contractProduct<64>, contractProduct<81>};
constexpr ContractFunction kContractSourceLast[kMaxBasisDegree + 1] = {
    contractProductSourceLast<1>,  contractProductSourceLast<4>,  contractProductSourceLast<9>,
    contractProductSourceLast<16>, contractProductSourceLast<25>, contractProductSourceLast<36>,
    contractProductSourceLast<49>, contractProductSourceLast<64>, contractProductSourceLast<81>};

}  // namespace radquad::detail
