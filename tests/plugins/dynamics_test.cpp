// Modal dynamics against the single-degree-of-freedom answers of docs/model.md: static deflection,
// step overshoot, steady harmonic amplitude; RK4's order and stability limit; exactness of ZOH.
#include <catch2/catch.hpp>
#include <cmath>

#include "plugin_catalog.hpp"
#include "topomill/dynamics_model.hpp"

using topomill::Params;
using topomill::Vec3;

namespace {
struct ModeSpec {
  std::string axis;
  double f, xi, k;
};

std::shared_ptr<topomill::DynamicsModel> modal(const std::string& name,
                                               const std::vector<ModeSpec>& modes,
                                               bool substep = false) {
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  Params p;
  std::vector<Params> tables;
  for (const auto& m : modes) {
    Params t;
    t.set("axis", m.axis);
    t.set("frequency", m.f);
    t.set("damping", m.xi);
    t.set("stiffness", m.k);
    tables.push_back(t);
  }
  p.set("modes", tables);
  p.set("time_step", 0.0);
  if (name == "modal_rk4") p.set("substep", substep);
  return catalog.create<topomill::DynamicsModel>(*catalog.find(name), p);
}

// Exact response (m) from rest to a step F at t = 0.
double step_response(double F, double k, double w, double xi, double t) {
  const double wd = w * std::sqrt(1 - xi * xi);
  return F / k * (1 - std::exp(-xi * w * t) * (std::cos(wd * t) + xi * w / wd * std::sin(wd * t)));
}

std::vector<Vec3> constant(double fx, std::size_t n) {
  return std::vector<Vec3>(n, Vec3(fx, 0, 0));
}
}  // namespace

TEST_CASE("a constant force settles at F/k, summed over an axis' modes", "[dynamics]") {
  for (const std::string name : {"modal_rk4", "modal_exact"}) {
    auto d = modal(name, {{"x", 785, 0.2, 1.74e7}, {"x", 1600, 0.2, 1.01e7}, {"y", 800, 0.2, 1e7}});
    const auto x = d->respond(constant(100, 20000), 1e-5);  // 0.2 s, many time constants
    CHECK(x.back().x() == Approx(1e3 * (100 / 1.74e7 + 100 / 1.01e7)).epsilon(1e-6));
    CHECK(x.back().y() == 0.0);
  }
}

TEST_CASE("the step response overshoots by exp(-xi pi / sqrt(1 - xi^2))", "[dynamics]") {
  for (const std::string name : {"modal_rk4", "modal_exact"}) {
    for (double xi : {0.0246, 0.1, 0.5}) {
      auto d = modal(name, {{"z", 753, xi, 1.21e7}});
      std::vector<Vec3> f(8000, Vec3(0, 0, 50));
      const auto z = d->respond(f, 2e-6);
      double peak = 0;
      for (const auto& v : z) peak = std::max(peak, v.z());
      const double stat = 1e3 * 50 / 1.21e7;
      CHECK(peak / stat - 1 == Approx(std::exp(-xi * M_PI / std::sqrt(1 - xi * xi))).epsilon(2e-3));
    }
  }
}

TEST_CASE("the steady harmonic amplitude is (F/k) / sqrt((1 - r^2)^2 + (2 xi r)^2)", "[dynamics]") {
  const double f0 = 800, xi = 0.05, k = 1e7, F = 20, w = 2 * M_PI * f0;
  for (double ratio : {0.5, 1.0, 2.0}) {
    const double W = ratio * w, dt = 2 * M_PI / W / 400;
    const std::size_t n =
        static_cast<std::size_t>(1.0 / dt);  // long enough to settle (xi w t ~ 250)
    std::vector<Vec3> force(n);
    // The force held over each step is the sine at the step's middle: the ZOH of a sine lags half a
    // step, which this removes.
    for (std::size_t i = 0; i < n; ++i) force[i] = Vec3(0, F * std::sin(W * (i + 0.5) * dt), 0);
    for (const std::string name : {"modal_rk4", "modal_exact"}) {
      const auto y = modal(name, {{"y", f0, xi, k}})->respond(force, dt);
      double amp = 0;
      for (std::size_t i = n - 800; i < n; ++i) amp = std::max(amp, std::abs(y[i].y()));
      const double want =
          1e3 * F / k / std::sqrt(std::pow(1 - ratio * ratio, 2) + std::pow(2 * xi * ratio, 2));
      INFO(name << " ratio " << ratio);
      CHECK(amp == Approx(want).epsilon(2e-3));
    }
  }
}

TEST_CASE("RK4 converges at fourth order and modal_exact is exact at any step", "[dynamics]") {
  const double w = 2 * M_PI * 1000, xi = 0.05, k = 1e7, F = 10, T = 2e-3;
  // Largest error over the whole trajectory (at a single instant the oscillating error may sit
  // near one of its zeros and hide the order).
  auto error = [&](const std::string& name, double dt) {
    const auto n = static_cast<std::size_t>(std::llround(T / dt)) + 1;
    const auto x = modal(name, {{"x", 1000, xi, k}})->respond(constant(F, n), dt);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i)
      worst = std::max(worst, std::abs(x[i].x() - 1e3 * step_response(F, k, w, xi, i * dt)));
    return worst;
  };
  const double e1 = error("modal_rk4", 2e-5), e2 = error("modal_rk4", 1e-5);
  INFO("RK4 errors " << e1 << ", " << e2 << ": order " << std::log2(e1 / e2));
  CHECK(std::log2(e1 / e2) == Approx(4).margin(0.3));
  for (double dt : {1e-6, 1e-4, 5e-4}) {  // omega dt up to 3.1, past RK4's limit
    CHECK(error("modal_exact", dt) < 1e-12 * 1e3 * F / k);
  }
}

TEST_CASE("a step applied later is answered from then on, not a step early", "[dynamics]") {
  // The force f[i] is held over [t_i, t_i+1): a step of F from sample i0 on leaves the mode at
  // rest up to t_i0 and then follows the step response of t - t_i0. A response a step early
  // (the force read one sample ahead) is F/k (w dt)^2 / 2 off at t_i0 + dt: 2 % of F/k here.
  const double f0 = 1000, xi = 0.05, k = 1e7, F = 10, w = 2 * M_PI * f0, dt = 2e-5;
  const std::size_t i0 = 37, n = 400;
  std::vector<Vec3> force(n, Vec3::Zero());
  for (std::size_t i = i0; i < n; ++i) force[i] = Vec3(F, 0, 0);
  for (const std::string name : {"modal_rk4", "modal_exact"}) {
    const auto x = modal(name, {{"x", f0, xi, k}})->respond(force, dt);
    // RK4's own error at w dt = 0.13: 1.5e-5 of the scale seen.
    const double tol = (name == "modal_exact" ? 1e-12 : 1e-4) * 1e3 * F / k;
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = (static_cast<double>(i) - static_cast<double>(i0)) * dt;
      const double want = i <= i0 ? 0.0 : 1e3 * step_response(F, k, w, xi, t);
      worst = std::max(worst, std::abs(x[i].x() - want));
    }
    INFO(name << ": largest difference " << worst << " mm, allowed " << tol);
    CHECK(worst < tol);
  }
}

TEST_CASE("RK4 beyond its stability limit is refused, or sub-stepped on request",
          "[dynamics][hard]") {
  const double f = 16000, w = 2 * M_PI * f;
  auto d = modal("modal_rk4", {{"x", 785, 0.0246, 1.74e7}, {"z", f, 0.0, 1e8}});
  // Undamped, the limit is omega dt = 2 sqrt 2 (docs/model.md).
  CHECK(d->max_stable_step() == Approx(2 * std::sqrt(2.0) / w).epsilon(1e-6));
  const double dt = 3.2 / w;
  CHECK_THROWS_WITH(d->respond(constant(1, 100), dt),
                    Catch::Contains("mode 2 (z, 16000 Hz)") && Catch::Contains("RK4 is unstable") &&
                        Catch::Contains("largest stable step is 2.813e-05 s"));
  auto sub = modal("modal_rk4", {{"z", f, 0.0, 1e8}}, true);
  std::vector<Vec3> force(400, Vec3(0, 0, 100));
  const auto z = sub->respond(force, dt);
  for (const auto& v : z) REQUIRE(std::isfinite(v.z()));
  double peak = 0;
  for (const auto& v : z) peak = std::max(peak, v.z());
  CHECK(peak == Approx(2 * 1e3 * 100 / 1e8).epsilon(0.02));  // undamped step: twice static
}
