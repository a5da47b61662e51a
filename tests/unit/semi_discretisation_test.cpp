// The semi-discretisation core against published spectral radii (SemiDiscretizationMethod.jl's
// README examples, first order), its step matrices against quadrature, and a constant-coefficient
// delayed oscillator against its exact stability boundary from the characteristic equation.
#include "stability/semi_discretisation.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/MatrixFunctions>

using namespace topomill::stability;

namespace {

DelaySystem scalar_system(double a, double b, double tau, double h, int steps) {
  DelaySystem s;
  s.n = 1;
  s.S = Eigen::MatrixXd::Ones(1, 1);
  s.tau = tau, s.h = h, s.steps = steps;
  s.step = [a, b](int, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A = Eigen::MatrixXd::Constant(1, 1, a), B = Eigen::MatrixXd::Constant(1, 1, b);
  };
  return s;
}

// m x'' + c x' + k x = -a H (x(t) - x(t - tau)), in state form with x in the delayed part.
DelaySystem oscillator(double wn, double zeta, double gain, double tau, int steps) {
  DelaySystem s;
  s.n = 2;
  s.S = Eigen::MatrixXd(1, 2);
  s.S << 1, 0;
  s.tau = tau, s.h = tau / steps, s.steps = steps;
  s.step = [=](int, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    A = Eigen::MatrixXd(2, 2), B = Eigen::MatrixXd(2, 1);
    A << 0, 1, -wn * wn - gain, -2 * zeta * wn;
    B << 0, gain;
  };
  return s;
}

}  // namespace

TEST_CASE("semi-discretisation: the Hayes equation's one-step radius (SemiDiscretizationMethod.jl)",
          "[lobes]") {
  // x' = -x - x(t - 1), first order, step 0.1, one step mapped: 0.941189374166563.
  CHECK(dominant_multiplier(scalar_system(-1, -1, 1.0, 0.1, 1)).modulus() ==
        Approx(0.941189374166563).epsilon(1e-13));
}

TEST_CASE("semi-discretisation: the delayed Mathieu equation (SemiDiscretizationMethod.jl)",
          "[lobes]") {
  // x'' + a1 x' + (delta + eps cos t) x = b0 x(t - 2 pi): delta 3, eps 2, b0 -0.15, a1 0.1,
  // step 0.01, 628 steps mapped: 0.5131596340374617 (A averaged over each step exactly here,
  // by quadrature there: the two agree to 1e-12).
  const double delta = 3, eps = 2, b0 = -0.15, a1 = 0.1, h = 0.01;
  DelaySystem s;
  s.n = 2;
  s.S = Eigen::MatrixXd(1, 2);
  s.S << 1, 0;
  s.tau = 2 * M_PI, s.h = h, s.steps = 628;
  s.step = [=](int i, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    const double mean_cos = (std::sin((i + 1) * h) - std::sin(i * h)) / h;
    A = Eigen::MatrixXd(2, 2), B = Eigen::MatrixXd(2, 1);
    A << 0, 1, -delta - eps * mean_cos, -a1;
    B << 0, b0;
  };
  CHECK(dominant_multiplier(s).modulus() == Approx(0.5131596340374617).epsilon(1e-11));
}

TEST_CASE("semi-discretisation: a step's matrices are the integrals they stand for", "[lobes]") {
  Eigen::MatrixXd A(2, 2), B(2, 1);
  A << -3, 1, -40, -0.7;
  B << 0.5, -2;
  const double h = 0.05, e = 0.3 * h;
  const StepMaps m = step_maps(A, B, h, e);
  // Composite Simpson on exp(A (h - s)) l_k(s) B.
  constexpr int kPanels = 2000;
  Eigen::MatrixXd w0 = Eigen::MatrixXd::Zero(2, 1), w1 = w0;
  for (int i = 0; i <= kPanels; ++i) {
    const double s = h * i / kPanels, wt = (i == 0 || i == kPanels) ? 1 : (i % 2 ? 4 : 2);
    const Eigen::MatrixXd E = (A * (h - s)).exp() * B * (wt * h / (3 * kPanels));
    w0 += E * (h + e - s) / h, w1 += E * (s - e) / h;
  }
  CHECK((m.P - (A * h).exp()).norm() < 1e-14);
  CHECK((m.W0 - w0).norm() < 1e-12);
  CHECK((m.W1 - w1).norm() < 1e-12);
}

TEST_CASE("semi-discretisation: a delayed oscillator's boundary is the characteristic equation's",
          "[lobes]") {
  // m x'' + c x' + k x = -a H0 (x - x(t - tau)) is on its stability boundary where
  // 1 + g G(iw) (1 - exp(-i w tau)) = 0 for a real gain g = a H0 / k (G = 1 / (1 - r^2 + 2 i zeta
  // r), r = w / wn): g = -1 / (G (1 - exp(-i w tau))) real. The least such positive g over w is the
  // critical gain; the semi-discretisation must find it.
  const double wn = 2 * M_PI * 922, zeta = 0.011;
  for (const double tau : {0.006, 0.003, 0.0021}) {
    double exact = INFINITY;
    auto imag_part = [&](double w) {
      const double r = w / wn;
      const std::complex<double> G = 1.0 / std::complex<double>(1 - r * r, 2 * zeta * r);
      return -1.0 / (G * (1.0 - std::exp(std::complex<double>(0, -w * tau))));
    };
    constexpr int kScan = 20000;
    for (int i = 1; i < kScan; ++i) {
      double a = wn * (0.2 + 2.0 * (i - 1) / kScan), b = wn * (0.2 + 2.0 * i / kScan);
      if ((imag_part(a).imag() > 0) == (imag_part(b).imag() > 0)) continue;
      for (int k = 0; k < 80; ++k) {
        const double m = 0.5 * (a + b);
        ((imag_part(m).imag() > 0) == (imag_part(a).imag() > 0) ? a : b) = m;
      }
      const double g = imag_part(0.5 * (a + b)).real();
      if (g > 0) exact = std::min(exact, g);
    }
    REQUIRE(std::isfinite(exact));
    // The semi-discretisation's boundary in the gain (per wn^2), 150 steps a period.
    double lo = 0, hi = 4 * exact;
    for (int k = 0; k < 30; ++k) {
      const double g = 0.5 * (lo + hi);
      (dominant_multiplier(oscillator(wn, zeta, g * wn * wn, tau, 150)).modulus() >= 1 ? hi : lo) =
          g;
    }
    INFO("tau " << tau << ": exact " << exact << ", semi-discretised " << lo);
    CHECK(lo == Approx(exact).epsilon(1e-2));  // 150 steps: within 0.5 % seen
  }
}
