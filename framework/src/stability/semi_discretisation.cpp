#include "stability/semi_discretisation.hpp"

#include <Eigen/Eigenvalues>
// GCC 12 warns of a use after free inside Spectra's Hessenberg eigen-solver as Eigen frees a
// temporary (-Wuse-after-free, a known false positive of its inliner); the warning is about
// their code, instantiated here.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuse-after-free"
#endif
#include <Spectra/GenEigsSolver.h>
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

// Every step's maps, in order. Steps whose A and B equal the last computed (a milling tool out of
// the cut: A the structure's alone, B zero, most of a period at low immersion) share its maps.
std::vector<StepMaps> all_step_maps(const DelaySystem& sys, double e);

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

namespace {

std::vector<StepMaps> all_step_maps(const DelaySystem& sys, double e) {
  const int n = sys.n, d = static_cast<int>(sys.S.rows());
  std::vector<StepMaps> out;
  out.reserve(static_cast<std::size_t>(sys.steps));
  Eigen::MatrixXd A(n, n), B(n, d), last_A, last_B;
  for (int i = 0; i < sys.steps; ++i) {
    sys.step(i, A, B);
    if (i > 0 && A == last_A && B == last_B) {
      out.push_back(out.back());
      continue;
    }
    out.push_back(step_maps(A, B, sys.h, e));
    last_A = A, last_B = B;
  }
  return out;
}

}  // namespace

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
    hist[static_cast<std::size_t>(k)]
        .middleCols(n + static_cast<Eigen::Index>(k) * d, d)
        .setIdentity();
  int head = 0;  // ring index of block k = 1
  auto block = [&](int k) -> Eigen::MatrixXd& {
    return hist[static_cast<std::size_t>((head + k - 1) % r)];
  };
  Eigen::MatrixXd Z(d, N);
  for (const StepMaps& m : all_step_maps(sys, e)) {
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

namespace {

// The monodromy as an operator: each step's maps computed once, a vector taken through all of
// them (the history a ring of r blocks of d).
class MonodromyOp {
 public:
  using Scalar = double;
  explicit MonodromyOp(const DelaySystem& sys)
      : n_(sys.n), d_(static_cast<int>(sys.S.rows())), r_(delay_steps(sys.tau, sys.h)), S_(sys.S) {
    maps_ = all_step_maps(sys, sys.tau - r_ * sys.h);
  }
  Eigen::Index rows() const { return n_ + static_cast<Eigen::Index>(r_) * d_; }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* in, double* out) const {
    Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(in, n_), next(n_), z(d_);
    ring_.assign(in + n_, in + rows());  // block k (1-based) at (k - 1) d: newest first
    int head = 0;
    auto block = [&](int k) {
      return Eigen::Map<Eigen::VectorXd>(ring_.data() + ((head + k - 1) % r_) * d_, d_);
    };
    for (const StepMaps& m : maps_) {
      z.noalias() = S_ * x;
      next.noalias() = m.P * x;
      next.noalias() += m.W0 * block(r_);
      if (r_ >= 2)
        next.noalias() += m.W1 * block(r_ - 1);
      else
        next.noalias() += m.W1 * z;
      block(r_) = z;
      head = (head + r_ - 1) % r_;
      x.swap(next);
    }
    Eigen::Map<Eigen::VectorXd>(out, n_) = x;
    for (int k = 1; k <= r_; ++k)
      Eigen::Map<Eigen::VectorXd>(out + n_ + static_cast<Eigen::Index>(k - 1) * d_, d_) = block(k);
  }

 private:
  int n_, d_, r_;
  Eigen::MatrixXd S_;
  std::vector<StepMaps> maps_;
  mutable std::vector<double> ring_;
};

// Arnoldi's share of the spectrum: enough wanted values that a complex pair and its neighbour
// are resolved, a Krylov space a few times that.
constexpr Eigen::Index kWanted = 4, kKrylov = 24;
constexpr Eigen::Index kMaxRestarts = 500;
constexpr double kArnoldiTolerance = 1e-12;

}  // namespace

Multiplier dominant_multiplier(const DelaySystem& sys) {
  if (delay_steps(sys.tau, sys.h) < 1)
    throw std::invalid_argument("semi-discretisation: the step exceeds the delay");
  MonodromyOp op(sys);
  const Eigen::Index N = op.rows();
  if (N > kKrylov + 2) {
    Spectra::GenEigsSolver<MonodromyOp> eigs(op, kWanted, kKrylov);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestMagn, kMaxRestarts, kArnoldiTolerance);
    if (eigs.info() == Spectra::CompInfo::Successful) {
      Multiplier best{0.0};
      for (const auto& v : eigs.eigenvalues())
        if (std::abs(v) > best.modulus()) best.value = v;
      return best;
    }
  }
  return dominant_multiplier_dense(sys);
}

#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic pop
#endif

Multiplier dominant_multiplier_dense(const DelaySystem& sys) {
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
