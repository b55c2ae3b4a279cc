#include "kernel/block_contraction.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "kernel/legendre_basis.h"
#include "kernel/simd_lanes.h"

namespace radquad::detail {
namespace {

// phi_k at `count` points, k = 0..degree, written out[k * stride + r]: Bonnet's recurrence
// (k+1) P_{k+1}(y) = (2k+1) y P_k(y) - k P_{k-1}(y), y = 2x - 1, then phi_k = sqrt(2k+1) P_k,
// as shiftedLegendreValues, but across points so that it vectorises.
void legendreAcrossPoints(int degree, const double* __restrict x, std::size_t count,
                          std::size_t stride, double* __restrict out) {
  for (std::size_t r = 0; r < count; ++r) out[r] = 1.0;
  if (degree >= 1) {
    for (std::size_t r = 0; r < count; ++r) out[stride + r] = 2.0 * x[r] - 1.0;
  }
  for (int k = 1; k < degree; ++k) {
    // Divided by k+1 through its reciprocal: a multiply, not a division, per point.
    const double a = (2.0 * k + 1.0) / (k + 1.0), c = double(k) / (k + 1.0);
    const double* __restrict previous = out + std::size_t(k - 1) * stride;
    const double* __restrict current = out + std::size_t(k) * stride;
    double* __restrict next = out + std::size_t(k + 1) * stride;
    for (std::size_t r = 0; r < count; ++r) {
      next[r] = a * (2.0 * x[r] - 1.0) * current[r] - c * previous[r];
    }
  }
  for (int k = 1; k <= degree; ++k) {
    const double scale = std::sqrt(2.0 * k + 1.0);
    double* __restrict row = out + std::size_t(k) * stride;
    for (std::size_t r = 0; r < count; ++r) row[r] *= scale;
  }
}

// Eight-lane vectors (GCC/Clang vector extension), so the accumulators are registers.
using Lanes = simd::Doubles8;

inline Lanes load(const double* from) {
  Lanes lanes;
  std::memcpy(&lanes, from, sizeof(lanes));
  return lanes;
}

inline void store(double* to, Lanes lanes) {
  std::memcpy(to, &lanes, sizeof(lanes));
}

// sums[b][a] += sum_p receiver_a[p] source_b[p] lane by lane (sums: F x F vectors of 8 lanes,
// b-major) for the T receiver functions a0 .. a0+T-1 and all F source functions. The T x F
// accumulators stay in registers for the whole block, and each source vector loaded feeds T
// multiply-adds. `rows` is a multiple of 8.
template <int F, int T>
inline void contractTile(std::size_t rows, std::size_t stride, const double* __restrict receiver,
                         const double* __restrict source, int a0, double* __restrict sums) {
  Lanes accumulators[T][F];
  for (int t = 0; t < T; ++t) {
    for (int b = 0; b < F; ++b) accumulators[t][b] = load(sums + 8 * std::size_t(b * F + a0 + t));
  }
  for (std::size_t p = 0; p < rows; p += 8) {
    Lanes r[T];
    for (int t = 0; t < T; ++t) r[t] = load(receiver + std::size_t(a0 + t) * stride + p);
#pragma GCC unroll 16
    for (int b = 0; b < F; ++b) {
      const Lanes sb = load(source + std::size_t(b) * stride + p);
      for (int t = 0; t < T; ++t) accumulators[t][b] += r[t] * sb;
    }
  }
  for (int t = 0; t < T; ++t) {
    for (int b = 0; b < F; ++b) store(sums + 8 * std::size_t(b * F + a0 + t), accumulators[t][b]);
  }
}

// All F receiver functions, T at a time: T F accumulators plus T receiver vectors fit the 32
// vector registers of AVX-512 (27 + 3 for d = 2), and each source load feeds T multiply-adds.
template <int N1>
void contractBlock(std::size_t rows, std::size_t stride, const double* receiver,
                   const double* source, double* sums) {
  constexpr int F = N1 * N1;
  constexpr int T = F <= 4 ? 4 : F <= 9 ? 3 : 1;
  int a = 0;
  for (; a + T <= F; a += T) contractTile<F, T>(rows, stride, receiver, source, a, sums);
  for (; a < F; ++a) contractTile<F, 1>(rows, stride, receiver, source, a, sums);
}

// phi_0 .. phi_{N1-1} of 8 points at once (Bonnet's recurrence as legendreAcrossPoints).
template <int N1>
inline void legendreLanes(Lanes x, Lanes (&phi)[N1]) {
  const Lanes y = 2.0 * x - 1.0;
  Lanes previous = Lanes{} + 1.0, current = y;
  phi[0] = previous;
  if constexpr (N1 > 1) phi[1] = std::sqrt(3.0) * y;
  for (int k = 1; k + 1 < N1; ++k) {
    const Lanes next =
        ((2.0 * k + 1.0) / (k + 1.0)) * y * current - (double(k) / (k + 1.0)) * previous;
    previous = current;
    current = next;
    phi[k + 1] = std::sqrt(2.0 * k + 3.0) * next;
  }
}

// Receiver products g phi_i(s) phi_j(t) and source products phi_k(u) phi_l(v) of the block, one
// column of `stride` per function (a = i N1 + j, b = k N1 + l), the basis values computed in
// registers and never stored. Rows past `rows` up to a multiple of 8 are zeros.
template <int N1>
void basisProducts(std::size_t rows, std::size_t stride, const double* s, const double* t,
                   const double* u, const double* v, const double* g, double* __restrict receiver,
                   double* __restrict source) {
  const std::size_t padded = (rows + 7) / 8 * 8;
  for (std::size_t p = 0; p < padded; p += 8) {
    Lanes ls, lt, lu, lv, lg;
    if (p + 8 <= rows) {
      ls = load(s + p), lt = load(t + p), lu = load(u + p), lv = load(v + p), lg = load(g + p);
    } else {  // the last, partial vector: g = 0 on the missing rows
      ls = lt = lu = lv = lg = Lanes{};
      for (std::size_t lane = 0; p + lane < rows; ++lane) {
        ls[lane] = s[p + lane], lt[lane] = t[p + lane], lu[lane] = u[p + lane];
        lv[lane] = v[p + lane], lg[lane] = g[p + lane];
      }
    }
    Lanes phiS[N1], phiT[N1], phiU[N1], phiV[N1];
    legendreLanes<N1>(ls, phiS);
    legendreLanes<N1>(lt, phiT);
    legendreLanes<N1>(lu, phiU);
    legendreLanes<N1>(lv, phiV);
    for (int i = 0; i < N1; ++i) {
      const Lanes weighted = lg * phiS[i];
      for (int j = 0; j < N1; ++j) {
        store(receiver + std::size_t(i * N1 + j) * stride + p, weighted * phiT[j]);
        store(source + std::size_t(i * N1 + j) * stride + p, phiU[i] * phiV[j]);
      }
    }
  }
}

template <int N1>
void contractPoints(std::size_t rows, std::size_t stride, const double* s, const double* t,
                    const double* u, const double* v, const double* g, double* receiver,
                    double* source, double* sums) {
  basisProducts<N1>(rows, stride, s, t, u, v, g, receiver, source);
  contractBlock<N1>((rows + 7) / 8 * 8, stride, receiver, source, sums);
}

using ContractFunction = void (*)(std::size_t, std::size_t, const double*, const double*,
                                  const double*, const double*, const double*, double*, double*,
                                  double*);

// Indexed by basis degree 1..3; higher degrees use a general matrix product.
constexpr ContractFunction kContract[4] = {nullptr, contractPoints<2>, contractPoints<3>,
                                           contractPoints<4>};

}  // namespace

void BlockContraction::begin(int degree) {
  degree_ = degree;
  const int functions = basisFunctionCount(degree);
  sum_.setZero(functions, functions);
  if (degree >= 1 && degree <= 3) lanes_.assign(8 * std::size_t(functions * functions), 0.0);
}

void BlockContraction::end(Eigen::MatrixXd& coupling) {
  const int functions = basisFunctionCount(degree_);
  if (degree_ >= 1 && degree_ <= 3) {
    for (int b = 0; b < functions; ++b) {
      for (int a = 0; a < functions; ++a) {
        const double* lanes = lanes_.data() + 8 * std::size_t(b * functions + a);
        double total = 0.0;
        for (int lane = 0; lane < 8; ++lane) total += lanes[lane];
        sum_(a, b) += total;
      }
    }
  }
  coupling = sum_;
}

void BlockContraction::accumulate(std::size_t rows, const double* s, const double* t,
                                  const double* u, const double* v, const double* __restrict g) {
  const int degree = degree_;
  if (degree == 0) {
    double sum = 0.0;
    for (std::size_t row = 0; row < rows; ++row) sum += g[row];
    sum_(0, 0) += sum;
    return;
  }
  constexpr std::size_t kStride = kPointBlock;
  const int n1 = degree + 1;
  const int functions = n1 * n1;
  if (degree <= 3) {
    receiverProducts_.resize(std::size_t(functions) * kStride);
    sourceProducts_.resize(std::size_t(functions) * kStride);
    kContract[degree](rows, kStride, s, t, u, v, g, receiverProducts_.data(),
                      sourceProducts_.data(), lanes_.data());
    return;
  }
  legendre_.resize(4 * std::size_t(n1) * kStride);
  double* alongS = legendre_.data();
  double* alongT = alongS + std::size_t(n1) * kStride;
  double* alongU = alongT + std::size_t(n1) * kStride;
  double* alongV = alongU + std::size_t(n1) * kStride;
  legendreAcrossPoints(degree, s, rows, kStride, alongS);
  legendreAcrossPoints(degree, t, rows, kStride, alongT);
  legendreAcrossPoints(degree, u, rows, kStride, alongU);
  legendreAcrossPoints(degree, v, rows, kStride, alongV);
  // coupling += receiverBlock^T sourceBlock with receiverBlock(k, a) = g_k phi_a(s_k, t_k) and
  // sourceBlock(k, b) = phi_b(u_k, v_k) (column-major: a column is contiguous in k).
  receiverBlock_.resize(Eigen::Index(kStride), functions);
  sourceBlock_.resize(Eigen::Index(kStride), functions);
  for (int i = 0; i < n1; ++i) {
    for (int j = 0; j < n1; ++j) {
      const int a = i * n1 + j;
      const double* __restrict ls = alongS + std::size_t(i) * kStride;
      const double* __restrict lt = alongT + std::size_t(j) * kStride;
      const double* __restrict lu = alongU + std::size_t(i) * kStride;
      const double* __restrict lv = alongV + std::size_t(j) * kStride;
      double* __restrict receiverColumn = receiverBlock_.col(a).data();
      double* __restrict sourceColumn = sourceBlock_.col(a).data();
      for (std::size_t row = 0; row < rows; ++row) {
        receiverColumn[row] = g[row] * (ls[row] * lt[row]);
        sourceColumn[row] = lu[row] * lv[row];
      }
    }
  }
  const auto n = Eigen::Index(rows);
  sum_.noalias() += receiverBlock_.topRows(n).transpose() * sourceBlock_.topRows(n);
}

}  // namespace radquad::detail
