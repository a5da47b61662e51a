// The milling stability model (framework/src/stability/) against outside answers: its mean
// directional matrix against Altintas and Budak's closed form, its Floquet multipliers against a
// brute-force time integration of Insperger and Stepan's equation written here, its convergence
// in the steps, and how the lobes' boundaries are crossed.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>

#include "stability/lobes.hpp"

using namespace topomill;
using namespace topomill::stability;

namespace {

// A straight-fluted end mill of diameter 2 R with a sharp corner: its cutting edges are its side.
class StraightEndMill : public ToolGeometry {
 public:
  StraightEndMill(double R, int teeth) : R_(R), teeth_(teeth) {}
  double radius() const override { return 0.0; }
  int teeth() const override { return teeth_; }
  double lag(double) const override { return 0.0; }
  double lag_slope(double) const override { return 0.0; }
  double ring() const override { return R_; }

 private:
  double R_;
  int teeth_;
};

// The benchmark (Insperger and Stepan): Kt 6e8 N/m^2, Kn 2e8 N/m^2, 922 Hz, zeta 0.011, m 0.03993
// kg, 2 teeth; feed along +x, a clockwise spindle (Altintas' frame: the tooth angle phi runs
// clockwise from +y, tooth at (R sin phi, R cos phi)).
constexpr double kKt = 600, kKn = 200;  // N/mm^2
const double kWn = 2 * M_PI * 922, kZeta = 0.011, kStiffness = 0.03993 * kWn * kWn;

LobeSetup benchmark(const ToolGeometry& tool, double aD, bool down, int dof) {
  LobeSetup s;
  s.tool = &tool;
  // Down-milling cuts phi in [acos(2 aD - 1), pi]: the material on -y, at -90 deg from the feed;
  // up-milling phi in [0, acos(1 - 2 aD)], the material on +y.
  s.engagement = {0.0, down ? -1 : 1, aD * 2 * tool.ring(), 0.0};
  s.sense = -1;
  s.k = {kKt, kKn, 0.0};
  s.modes = {{0, kWn, kZeta, kStiffness}};
  if (dof == 2) s.modes.push_back({1, kWn, kZeta, kStiffness});
  return s;
}

MillingModel model_of(const LobeSetup& s, double depth) {
  MillingModel m;
  Engagement e = s.engagement;
  e.depth = depth;
  m.elements = cutting_elements(*s.tool, e, s.elements_per_mm);
  m.teeth = s.tool->teeth();
  m.feed_azimuth = e.feed_azimuth, m.sense = s.sense, m.k = s.k, m.modes = s.modes;
  return m;
}

// Insperger and Stepan's specific force of the 1-DOF model along the feed, per unit depth (N/m
// per m): h(t) = sum_j g(phi_j) sin(phi_j) (Kt cos(phi_j) + Kn sin(phi_j)).
double insperger_h(double phi_spindle, int teeth, double phi_st, double phi_ex) {
  double h = 0;
  for (int j = 0; j < teeth; ++j) {
    const double phi = std::fmod(phi_spindle + 2 * M_PI * j / teeth, 2 * M_PI);
    if (phi >= phi_st && phi <= phi_ex)
      h += std::sin(phi) * (6e8 * std::cos(phi) + 2e8 * std::sin(phi));
  }
  return h;
}

// The spectral radius of m x'' + c x' + k x = -w h(t) (x(t) - x(t - tau)) by brute force: RK4 over
// K steps of the tooth period, the delayed x interpolated linearly in its K + 1 stored values
// (exact at the steps' ends; at the midpoints the interpolation's error), the map from the
// state (x, v, stored history) over one period built column by column.
double brute_force_radius(double rpm, double depth_m, double aD, int K) {
  const int teeth = 2;
  const double phi_st = std::acos(2 * aD - 1), phi_ex = M_PI;
  const double tau = 60 / (rpm * teeth), dt = tau / K, spin = rpm * 2 * M_PI / 60;
  const double m = 0.03993, c = 2 * kZeta * m * kWn;
  const int N = 2 + K + 1;
  Eigen::MatrixXd phi(N, N);
  for (int col = 0; col < N; ++col) {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(N);
    y(col) = 1;
    // hist[k]: x at t = k dt - tau (k = 0..K); x, v now.
    std::vector<double> hist(static_cast<std::size_t>(K + 1));
    for (int k = 0; k <= K; ++k) hist[static_cast<std::size_t>(k)] = y(2 + k);
    double x = y(0), v = y(1);
    std::vector<double> now(static_cast<std::size_t>(K + 1));
    now[0] = x;
    auto f = [&](double t, double xx, double vv, double xd, double& dx, double& dv) {
      const double h = insperger_h(spin * t, teeth, phi_st, phi_ex);
      dx = vv;
      dv = (-c * vv - kStiffness * xx - depth_m * h * (xx - xd)) / m;
    };
    for (int k = 0; k < K; ++k) {
      const double t = k * dt, x0 = hist[static_cast<std::size_t>(k)],
                   x1 = hist[static_cast<std::size_t>(k + 1)], xm = 0.5 * (x0 + x1);
      double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
      f(t, x, v, x0, k1x, k1v);
      f(t + dt / 2, x + dt / 2 * k1x, v + dt / 2 * k1v, xm, k2x, k2v);
      f(t + dt / 2, x + dt / 2 * k2x, v + dt / 2 * k2v, xm, k3x, k3v);
      f(t + dt, x + dt * k3x, v + dt * k3v, x1, k4x, k4v);
      x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      now[static_cast<std::size_t>(k + 1)] = x;
    }
    phi(0, col) = x, phi(1, col) = v;
    for (int k = 0; k <= K; ++k) phi(2 + k, col) = now[static_cast<std::size_t>(k)];
  }
  const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(phi, false).eigenvalues();
  double r = 0;
  for (const auto& e : ev) r = std::max(r, std::abs(e));
  return r;
}

}  // namespace

TEST_CASE("lobes: the mean directional matrix is Altintas and Budak's", "[lobes]") {
  // A0 = N Kt / (4 pi) [alpha], alpha_xx = 1/2 [cos 2p - 2 Kr p + Kr sin 2p], alpha_xy = 1/2
  // [-sin 2p - 2 p + Kr cos 2p], alpha_yx = 1/2 [-sin 2p + 2 p + Kr cos 2p], alpha_yy = 1/2
  // [-cos 2p - 2 Kr p - Kr sin 2p], each from phi_st to phi_ex (Kr = Kn / Kt); F = a A0 Delta.
  const StraightEndMill tool(5.0, 3);
  for (const auto& [aD, down] :
       {std::pair{0.5, true}, std::pair{0.3, false}, std::pair{1.0, true}, std::pair{0.05, true}}) {
    const LobeSetup s = benchmark(tool, aD, down, 2);
    const double st = down ? std::acos(2 * aD - 1) : 0.0, ex = down ? M_PI : std::acos(1 - 2 * aD);
    const double kr = kKn / kKt;
    auto at = [&](double p, int which) {
      switch (which) {
        case 0:
          return 0.5 * (std::cos(2 * p) - 2 * kr * p + kr * std::sin(2 * p));
        case 1:
          return 0.5 * (-std::sin(2 * p) - 2 * p + kr * std::cos(2 * p));
        case 2:
          return 0.5 * (-std::sin(2 * p) + 2 * p + kr * std::cos(2 * p));
        default:
          return 0.5 * (-std::cos(2 * p) - 2 * kr * p - kr * std::sin(2 * p));
      }
    };
    Eigen::Matrix2d expected;
    for (int w = 0; w < 4; ++w) expected(w / 2, w % 2) = at(ex, w) - at(st, w);
    expected *= tool.teeth() * kKt / (4 * M_PI);
    const double depth = 2.0;  // mm
    const std::vector<Eigen::Matrix3d> av = directional_averages(model_of(s, depth), 9000, 64);
    Eigen::Matrix3d mean = Eigen::Matrix3d::Zero();
    for (const auto& a : av) mean += a;
    mean /= static_cast<double>(av.size()) * depth;
    INFO("a/D " << aD << (down ? " down" : " up") << "\n" << mean << "\nexpected\n" << expected);
    CHECK((mean.topLeftCorner<2, 2>() - expected).norm() < 1e-9 * expected.norm());
  }
}

TEST_CASE("lobes: Floquet multipliers agree with a brute-force time integration", "[lobes]") {
  const StraightEndMill tool(5.0, 2);
  for (const auto& [rpm, depth, aD] :
       {std::tuple{5000.0, 0.4, 1.0}, std::tuple{12500.0, 2.0, 1.0}, std::tuple{10000.0, 1.5, 0.1},
        std::tuple{20000.0, 3.0, 0.05}}) {
    LobeSetup s = benchmark(tool, aD, true, 1);
    s.steps = 400;
    const double ours = multiplier_at(s, rpm, depth).modulus();
    const double brute = brute_force_radius(rpm, depth * 1e-3, aD, 400);
    INFO(rpm << " rpm, " << depth << " mm, a/D " << aD);
    CHECK(ours == Approx(brute).epsilon(1e-2));  // both discretised: within 0.6 % seen
  }
}

TEST_CASE("lobes: the critical depth converges as the steps are refined", "[lobes]") {
  const StraightEndMill tool(5.0, 2);
  LobeSetup s = benchmark(tool, 1.0, true, 1);
  double last = NAN, last_change = INFINITY;
  for (const int steps : {40, 80, 160, 320}) {
    s.steps = steps;
    const double d = critical_depth(s, 5000).depth;
    if (!std::isnan(last)) {
      const double change = std::abs(d - last);
      INFO(steps << " steps: " << d << " mm, changed by " << change);
      CHECK(change < 0.5 * last_change);
      last_change = change;
    }
    last = d;
  }
  CHECK(last_change < 2e-3);  // mm, from 160 to 320 steps
}

TEST_CASE("lobes: flip and Hopf boundaries told apart by their critical multiplier", "[lobes]") {
  const StraightEndMill tool(5.0, 2);
  const LobeSetup s = benchmark(tool, 0.05, true, 1);
  // Low immersion: period doubling in a flip lobe (10000 rpm), a complex
  // pair below them.
  const LobePoint flip = critical_depth(s, 10000);
  CHECK(flip.onset == Onset::kFlip);
  CHECK(flip.multiplier.real() < -0.99);
  const LobePoint hopf = critical_depth(s, 5000);
  CHECK(hopf.onset == Onset::kHopf);
  CHECK(std::abs(hopf.multiplier.imag()) > 0.05);
  // Just below the boundary stable, just above not.
  CHECK(multiplier_at(s, 10000, flip.depth * 0.999).modulus() < 1);
  CHECK(multiplier_at(s, 10000, flip.depth * 1.001).modulus() > 1);
}

TEST_CASE("lobes: Arnoldi's dominant multiplier is the full eigen-decomposition's", "[lobes]") {
  // The fast path against its oracle over both kinds of boundary, stable and unstable cuts, one
  // mode and two, low and high speed (tau holding 1 to 5.5 cycles of the mode).
  const StraightEndMill tool(5.0, 2);
  int compared = 0;
  for (const int dof : {1, 2})
    for (const double aD : {1.0, 0.05})
      for (const double rpm : {5000.0, 11000.0, 19000.0, 25000.0})
        for (const double depth : {0.2, 1.5, 4.0}) {
          const LobeSetup s = benchmark(tool, aD, true, dof);
          MillingModel m = model_of(s, depth);
          std::vector<Eigen::Matrix3d> averages;
          const DelaySystem sys = milling_system(m, rpm, steps_at(s, rpm), averages);
          const std::complex<double> fast = dominant_multiplier(sys).value;
          const std::complex<double> dense = dominant_multiplier_dense(sys).value;
          INFO(dof << "-DOF, a/D " << aD << ", " << rpm << " rpm, " << depth << " mm: " << fast
                   << " against " << dense);
          // (The two differ by up to 2e-8: the dense solver's own error on a far from normal
          // matrix is of that order.)
          CHECK(std::abs(std::abs(fast) - std::abs(dense)) < 1e-7 * std::abs(dense));
          CHECK(std::abs(fast.real() - dense.real()) < 1e-7);
          CHECK(std::abs(std::abs(fast.imag()) - std::abs(dense.imag())) < 1e-7);
          ++compared;
        }
  CHECK(compared == 48);
}
