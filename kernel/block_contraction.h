// The contraction shared by the scattered and the streamed coupling paths (kernel/coupling.h):
// for one block of at most kPointBlock points p with kernel values g_p on the unit 4-cube,
//   coupling[a][b] += sum_p g_p phi_i(s_p) phi_j(t_p) phi_k(u_p) phi_l(v_p),
//   a = i (d+1) + j (receiver), b = k (d+1) + l (source),
// the unit-square form of K = sqrt(A_r A_s) sum_k w_k phi_a(x_k) G_k phi_b(x'_k)
// (docs/design.md, "Conventions"). Not part of the kernel's interface.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace radquad::detail {

// Points per block: the block's basis values (4 (d+1) + 2 (d+1)^2 columns) stay in L1/L2.
inline constexpr std::size_t kPointBlock = 256;

// begin(d), accumulate() for every block, end(): the running sums are kept lane by lane
// (degrees 1..3) and summed across lanes once per link.
class BlockContraction {
 public:
  void begin(int degree);
  // Adds one block of `rows` <= kPointBlock points; those whose g is 0 may be left out.
  void accumulate(std::size_t rows, const double* s, const double* t, const double* u,
                  const double* v, const double* g);
  // coupling = the sum (F x F, F = (d+1)^2, rows a, columns b).
  void end(Eigen::MatrixXd& coupling);

 private:
  int degree_ = 0;
  std::vector<double> lanes_;  // degrees 1..3: sums[b][a] as 8 partial sums, b-major
  Eigen::MatrixXd sum_;
  std::vector<double> legendre_, receiverProducts_, sourceProducts_;
  Eigen::MatrixXd receiverBlock_, sourceBlock_;
};

}  // namespace radquad::detail
