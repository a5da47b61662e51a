#include "stability/semi_discretisation.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

namespace topomill::stability {

namespace {

// r and e for the delay: tau = r h + e, 0 <= e < h (tau a whole number of steps gives e = 0 in
// spite of round-off in tau / h).
int delay_steps(double tau, double h) {
  constexpr double kWhole = 1e-9;
  return static_cast<int>(std::floor(tau / h + kWhole));
}

}  // namespace

StepMaps step_maps(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double h, double e) {
  // exp of [[A, I, 0], [0, 0, I], [0, 0, 0]] h holds exp(A h), F1 = int_0^h exp(A (h - s)) ds
  // and F2 = int_0^h exp(A (h - s)) s ds in its first block row.
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  M.block(0, 0, n, n) = A * h;
  M.block(0, n, n, n) = Eigen::MatrixXd::Identity(n, n) * h;
  M.block(n, 2 * n, n, n) = Eigen::MatrixXd::Identity(n, n) * h;
  const Eigen::MatrixXd E = M.exp();
  const Eigen::MatrixXd F1 = E.block(0, n, n, n), F2 = E.block(0, 2 * n, n, n);
  StepMaps out;
  out.P = E.block(0, 0, n, n);
  // l0(s) = (h + e - s) / h, l1(s) = (s - e) / h.
  out.W0 = ((h + e) * F1 - F2) / h * B;
  out.W1 = (F2 - e * F1) / h * B;
  return out;
}

Eigen::MatrixXd monodromy(const DelaySystem& sys) {
  const int n = sys.n, d = static_cast<int>(sys.S.rows());
  const int r = delay_steps(sys.tau, sys.h);
  if (r < 1) throw std::invalid_argument("semi-discretisation: the step exceeds the delay");
  const double e = sys.tau - r * sys.h;
  const Eigen::Index N = n + static_cast<Eigen::Index>(r) * d;
  // The images of the unit vectors: x's rows, and the history of z as a ring of r blocks
  // (block k = 1 the newest, z_{i-1}; k = r the oldest, z_{i-r}).
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, N);
  X.leftCols(n).setIdentity();
  std::vector<Eigen::MatrixXd> hist(static_cast<std::size_t>(r), Eigen::MatrixXd::Zero(d, N));
  for (int k = 0; k < r; ++k)
    hist[static_cast<std::size_t>(k)].middleCols(n + static_cast<Eigen::Index>(k) * d, d)
        .setIdentity();
  int head = 0;  // ring index of block k = 1
  auto block = [&](int k) -> Eigen::MatrixXd& {
    return hist[static_cast<std::size_t>((head + k - 1) % r)];
  };
  Eigen::MatrixXd A(n, n), B(n, d), Z(d, N);
  for (int i = 0; i < sys.steps; ++i) {
    sys.step(i, A, B);
    const StepMaps m = step_maps(A, B, sys.h, e);
    Z.noalias() = sys.S * X;
    Eigen::MatrixXd next = m.P * X + m.W0 * block(r);
    next.noalias() += m.W1 * (r >= 2 ? block(r - 1) : Z);
    block(r) = Z;  // the oldest block's place takes z_i, the newest
    head = (head + r - 1) % r;
    X.swap(next);
  }
  Eigen::MatrixXd out(N, N);
  out.topRows(n) = X;
  for (int k = 1; k <= r; ++k)
    out.middleRows(n + static_cast<Eigen::Index>(k - 1) * d, d) = block(k);
  return out;
}

Multiplier dominant_multiplier(const DelaySystem& sys) {
  const Eigen::MatrixXd phi = monodromy(sys);
  Eigen::EigenSolver<Eigen::MatrixXd> solver(phi, false);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("semi-discretisation: the eigenvalue solver did not converge");
  Multiplier best{0.0};
  for (const auto& v : solver.eigenvalues())
    if (std::abs(v) > best.modulus()) best.value = v;
  return best;
}

}  // namespace topomill::stability
