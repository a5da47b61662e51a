// Modal vibration with the exact zero-order-hold step: exact for a force held constant over each
// step, unconditionally stable (docs/model.md).
#include <cmath>

#include "../common/modal.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

class ModalExact : public Modal {
 public:
  static Schema schema() { return base_schema(); }
  explicit ModalExact(const Params& p) : Modal(p) {}

 protected:
  void integrate(const Mode& m, const std::vector<double>& f, double dt,
                 std::vector<double>& q) const override {
    const double w = m.omega, xi = m.xi, wd = w * std::sqrt(1 - xi * xi);
    const double e = std::exp(-xi * w * dt), c = std::cos(wd * dt), s = std::sin(wd * dt);
    const double p11 = e * (c + xi * w / wd * s), p12 = e * s / wd;
    const double p21 = -w * w * e * s / wd, p22 = e * (c - xi * w / wd * s);
    const double b1 = (1 - p11) / m.k, b2 = -p21 / m.k;
    q.assign(f.size(), 0.0);
    double x = 0, v = 0;
    for (std::size_t i = 0; i + 1 < f.size(); ++i) {
      const double xn = p11 * x + p12 * v + b1 * f[i];
      v = p21 * x + p22 * v + b2 * f[i];
      x = xn;
      q[i + 1] = x;
    }
  }
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("modal_exact", "0.1.0") {
  registrar.add<topomill::DynamicsModel, topomill::plugins::ModalExact>(
      "modal_exact", "Modal vibration, exact zero-order-hold step (unconditionally stable)");
}
