// The paper's vibration model (Eq. 22-26): modal oscillators integrated with classical RK4, the
// paper's fourth stage corrected (a full step, not half).
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "../common/modal.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

namespace {
// |R(z)| of classical RK4, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24.
double rk4_gain(std::complex<double> z) {
  return std::abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6 + z / 24.0))));
}

// Largest h with |R(lambda h)| <= 1 for both eigenvalues of the mode: scan, then bisect.
double stable_step(const Mode& m) {
  const double w = m.omega, xi = m.xi;
  std::vector<std::complex<double>> eig;
  const double root = std::sqrt(std::abs(1 - xi * xi));
  eig.push_back({-xi * w, w * root});
  const double scale = std::abs(eig[0]);
  auto stable = [&](double h) {
    for (const auto& e : eig)
      if (rk4_gain(e * h) > 1.0 + 1e-15) return false;
    return true;
  };
  double lo = 0, hi = 0;
  for (double h = 0.01 / scale;; h += 0.01 / scale) {
    if (!stable(h)) {
      hi = h;
      break;
    }
    lo = h;
  }
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}
}  // namespace

class ModalRk4 : public Modal {
 public:
  static Schema schema() {
    Schema s = base_schema();
    s.add_bool("substep",
               "Split a step that is unstable for RK4 into stable sub-steps instead of "
               "refusing the scene")
        .with_default(false);
    return s;
  }
  explicit ModalRk4(const Params& p) : Modal(p), substep_(p.boolean("substep")) {}

  double max_stable_step() const override {
    if (substep_) return std::numeric_limits<double>::infinity();
    double h = std::numeric_limits<double>::infinity();
    for (const auto& m : modes_) h = std::min(h, stable_step(m));
    return h;
  }

 protected:
  void integrate(const Mode& m, const std::vector<double>& f, double dt,
                 std::vector<double>& q) const override {
    const double limit = stable_step(m);
    int sub = 1;
    if (dt > limit) {
      if (!substep_)
        throw ParamError("modes", m.label + ": RK4 is unstable at the step " + fmt(dt) +
                                      " s (omega dt = " + fmt(m.omega * dt) +
                                      "); the largest stable step is " + fmt(limit) +
                                      " s. Set time_step below it, or substep = true");
      // Merely stable is not enough: at omega h near the limit RK4 loses (omega h)^6 / 144 of the
      // amplitude per step. Sub-steps of omega h <= 0.3 lose less than 6e-6 per step.
      sub = static_cast<int>(std::ceil(m.omega * dt / 0.3));
    }
    const double h = dt / sub, w2 = m.omega * m.omega, c = 2 * m.xi * m.omega;
    q.assign(f.size(), 0.0);
    double x = 0, v = 0;
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
      const double a0 = w2 / m.k * f[i];  // force held over the step
      auto acc = [&](double xx, double vv) { return a0 - c * vv - w2 * xx; };
      for (int s = 0; s < sub; ++s) {
        const double k1 = v, l1 = acc(x, v);
        const double k2 = v + h / 2 * l1, l2 = acc(x + h / 2 * k1, v + h / 2 * l1);
        const double k3 = v + h / 2 * l2, l3 = acc(x + h / 2 * k2, v + h / 2 * l2);
        const double k4 = v + h * l3, l4 = acc(x + h * k3, v + h * l3);
        x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
        v += h / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
      }
      q[i + 1] = x;
    }
  }

 private:
  static std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
  }
  bool substep_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("modal_rk4", "0.1.0") {
  registrar.add<topomill::DynamicsModel, topomill::plugins::ModalRk4>(
      "modal_rk4",
      "Modal vibration integrated with classical RK4 (Hao et al. Eq. 22-26, "
      "fourth stage corrected)");
}
