#include "stability/milling_system.hpp"

#include <algorithm>
#include <cmath>

namespace topomill::stability {

namespace {

constexpr double kMmPerM = 1e3;

double wrap(double a) {
  return a - 2 * M_PI * std::floor((a + M_PI) / (2 * M_PI));
}

// The element's D at azimuth psi (per unit width).
Eigen::Matrix3d element_matrix(const CuttingElement& el, const MillingModel& m, double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  const Eigen::Vector3d n(el.sin_a * c, el.sin_a * s, -el.cos_a);
  const Eigen::Vector3d a(el.cos_a * c, el.cos_a * s, el.sin_a);
  const Eigen::Vector3d v = m.sense * Eigen::Vector3d(-s, c, 0);
  return -(m.k.tangential * v + m.k.radial * n + m.k.axial * a) * n.transpose();
}

}  // namespace

std::vector<Eigen::Matrix3d> directional_averages(const MillingModel& m, double rpm, int steps) {
  // 3-point Gauss-Legendre on [-1, 1].
  static const double kNodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  static const double kWeights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double w = rpm * 2 * M_PI / 60;  // |spindle rate|, rad/s
  const double tau = 2 * M_PI / (m.teeth * w), h = tau / steps;
  std::vector<Eigen::Matrix3d> out(static_cast<std::size_t>(steps), Eigen::Matrix3d::Zero());
  for (int i = 0; i < steps; ++i) {
    Eigen::Matrix3d& sum = out[static_cast<std::size_t>(i)];
    for (int j = 0; j < m.teeth; ++j)
      for (const CuttingElement& el : m.elements) {
        // The element's azimuth relative to the feed's over the step.
        const double start =
            wrap(el.psi0 + 2 * M_PI * j / m.teeth + m.sense * w * i * h - m.feed_azimuth);
        const double end = start + m.sense * w * h;
        const double a = std::max(std::min(start, end), el.lo);
        const double b = std::min(std::max(start, end), el.hi);
        if (!(b > a)) continue;
        for (int g = 0; g < 3; ++g) {
          const double phi = 0.5 * (a + b) + 0.5 * (b - a) * kNodes[g];
          sum += (0.5 * (b - a) * kWeights[g] * el.width) *
                 element_matrix(el, m, phi + m.feed_azimuth);
        }
      }
    sum /= w * h;  // the integral over the azimuth, per unit time of the step
  }
  return out;
}

DelaySystem milling_system(const MillingModel& m, double rpm, int steps,
                           std::vector<Eigen::Matrix3d>& averages) {
  averages = directional_averages(m, rpm, steps);
  const int M = static_cast<int>(m.modes.size());
  // The axes that have modes: the delayed quantities are their displacements (mm).
  std::vector<int> axes;
  for (int k = 0; k < 3; ++k)
    for (const ModalMode& mode : m.modes)
      if (mode.axis == k) {
        axes.push_back(k);
        break;
      }
  const int d = static_cast<int>(axes.size());
  const double w = rpm * 2 * M_PI / 60;
  DelaySystem sys;
  sys.n = 2 * M;
  sys.tau = 2 * M_PI / (m.teeth * w);
  sys.h = sys.tau / steps;
  sys.steps = steps;
  // G (M x d): mode i takes omega_i^2 / k_i of its axis's force; S (d x 2M): an axis's
  // displacement (mm) is the sum of its modes' (m).
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(M, d);
  sys.S = Eigen::MatrixXd::Zero(d, 2 * M);
  Eigen::MatrixXd still = Eigen::MatrixXd::Zero(2 * M, 2 * M);
  for (int i = 0; i < M; ++i) {
    const ModalMode& mode = m.modes[static_cast<std::size_t>(i)];
    const int row = static_cast<int>(std::find(axes.begin(), axes.end(), mode.axis) - axes.begin());
    G(i, row) = mode.omega * mode.omega / mode.stiffness;
    sys.S(row, i) = kMmPerM;
    still(i, M + i) = 1;
    still(M + i, i) = -mode.omega * mode.omega;
    still(M + i, M + i) = -2 * mode.damping * mode.omega;
  }
  const std::vector<Eigen::Matrix3d>* avg = &averages;
  const Eigen::MatrixXd S = sys.S.leftCols(M);
  sys.step = [avg, G, S, still, axes, M, d](int i, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    const Eigen::Matrix3d& D = (*avg)[static_cast<std::size_t>(i)];
    Eigen::MatrixXd Dd(d, d);  // D between the axes that move
    for (int r = 0; r < d; ++r)
      for (int c = 0; c < d; ++c)
        Dd(r, c) = D(axes[static_cast<std::size_t>(r)], axes[static_cast<std::size_t>(c)]);
    const Eigen::MatrixXd GD = G * Dd;  // M x d
    A = still;
    A.bottomLeftCorner(M, M) += GD * S;
    B = Eigen::MatrixXd::Zero(2 * M, d);
    B.bottomRows(M) = -GD;
  };
  return sys;
}

}  // namespace topomill::stability
