// First-order semi-discretisation (Insperger and Stepan, "Semi-Discretization for Time-Delay
// Systems", Springer 2011) of a linear periodic delay system
//
//   x'(t) = A(t) x(t) + B(t) z(t - tau),   z = S x  (the d delayed quantities).
//
// Time is cut into steps of length h; over step i, A and B are held at their averages A_i and
// B_i, and the delayed term is interpolated linearly between the two stored values of z that
// bracket t - tau. With r = floor(tau / h) and e = tau - r h, on t = t_i + s (0 <= s <= h)
//
//   z(t - tau) ~ z_{i-r} (h + e - s) / h + z_{i-r+1} (s - e) / h,
//
// and the step is solved exactly: x_{i+1} = P_i x_i + W0_i z_{i-r} + W1_i z_{i-r+1}, with
// P_i = exp(A_i h) and W_k = (int_0^h exp(A_i (h - s)) l_k(s) ds) B_i. The state of the map is
// y_i = (x_i, z_{i-1}, ..., z_{i-r}); the product of the step maps over a period is the
// monodromy matrix, whose eigenvalues (the Floquet multipliers) decide stability: stable when
// all lie inside the unit circle.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>

namespace topomill::stability {

struct DelaySystem {
  int n = 0;          // size of x
  Eigen::MatrixXd S;  // d x n: z = S x
  double tau = 0;     // the delay
  double h = 0;       // the step
  int steps = 0;      // steps in the mapped interval (a period)
  // A_i (n x n) and B_i (n x d): the averages over step i, [i h, (i + 1) h].
  std::function<void(int i, Eigen::MatrixXd& A, Eigen::MatrixXd& B)> step;
};

// The monodromy matrix's eigenvalue of largest modulus.
struct Multiplier {
  std::complex<double> value;
  double modulus() const { return std::abs(value); }
};

// The monodromy matrix over `steps` steps: (n + r d) square, state ordered as y above. r must be
// at least 1 (tau >= h).
Eigen::MatrixXd monodromy(const DelaySystem& sys);

// The dominant Floquet multiplier: by implicitly restarted Arnoldi (Spectra) on the monodromy
// applied step by step, never formed; where that does not converge, by all the eigenvalues of
// the matrix formed (dominant_multiplier_dense, the oracle beside it).
Multiplier dominant_multiplier(const DelaySystem& sys);
Multiplier dominant_multiplier_dense(const DelaySystem& sys);

// One step's matrices (exposed for tests): P, W0, W1 for the averages A, B, step h, and the
// delay's remainder e = tau - r h.
struct StepMaps {
  Eigen::MatrixXd P, W0, W1;
};
StepMaps step_maps(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double h, double e);

}  // namespace topomill::stability
