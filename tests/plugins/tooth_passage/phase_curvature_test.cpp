// tooth_passage's bound of the phase's second derivative over a piece (phase_curvature.hpp),
// against G'' sampled along random paths of the point over the node: G' = omega + Psi_u u' -
// az' written here from the point's offset q and its velocity, Psi_u differenced from the
// tool's own lag, and G'' from differences of G'. The bound must hold every sample (a bound
// that is too low lets the exact windows take a piece with a turn-back for monotone and skip
// two crossings), and on a straight pass with no lag come within 1.6 of the true largest
// (0.65 v^2 / d^2; the bound is v^2 / d^2: a looser one only cuts more pieces).
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "support/builtin_models.hpp"
#include "tooth_passage/lag_shape.hpp"
#include "tooth_passage/phase_curvature.hpp"

using topomill::ToolGeometry;

TEST_CASE("phase curvature: the bound holds G'' sampled along random paths", "[tooth_passage]") {
  const double omega = 418.9;  // rad/s, 4000 rpm
  for (const double helix : {0.0, 30.0}) {
    for (const std::string name : {"ball_end_loxodrome", "ball_end_constant_lead"}) {
      const std::shared_ptr<ToolGeometry> tool =
          testing::make_model<ToolGeometry>(name, {{"radius", 5}, {"helix_angle", helix}});
      const topomill::plugins::LagShape shape(*tool);
      const double R = tool->radius(), tip = R * std::sin(tool->min_polar_angle());
      auto lag = [&](double rho) {
        const double s = rho / R;
        return tool->lag_sc(s, std::sqrt(1 - s * s));
      };
      // The path q(t) = q0 + v0 t + a t^2 / 2 over [0, T]; G'(t) from q and q'.
      struct Path {
        double qx, qy, vx, vy, ax, ay;
      };
      auto rate = [&](const Path& p, double t) {
        const double qx = p.qx + p.vx * t + 0.5 * p.ax * t * t,
                     qy = p.qy + p.vy * t + 0.5 * p.ay * t * t;
        const double dx = p.vx + p.ax * t, dy = p.vy + p.ay * t, r2 = qx * qx + qy * qy;
        const double rho = std::sqrt(r2), e = 1e-6;
        const double psi_u = (lag(rho * std::exp(e)) - lag(rho * std::exp(-e))) / (2 * e);
        return omega + psi_u * (qx * dx + qy * dy) / r2 - (qx * dy - qy * dx) / r2;
      };
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> unit(-1, 1);
      for (int q = 0; q < 300; ++q) {
        // Half of them straight passes at distance d across their closest approach (the case the
        // bound is tight for); the rest bent, within 0.3 mm of the axis or 4 mm (where the lag
        // bends: k2), at up to 20 mm/s.
        const bool straight = q % 2 == 0;
        const double d = 0.002 + 0.03 * std::abs(unit(rng)), speed = 20 * std::abs(unit(rng)) + 1;
        const double T = straight ? 6 * d / speed : 0.004;
        const double reach = q % 4 == 1 ? 0.3 : 4.0;  // bent: near the tip, or over the ball
        Path p = straight ? Path{d, -0.5 * speed * T, 0, speed, 0, 0}
                          : Path{reach * unit(rng), reach * unit(rng), 20 * unit(rng),
                                 20 * unit(rng),    5e3 * unit(rng),   5e3 * unit(rng)};
        // The path's distances from the axis, top speed and the G'' samples.
        double rho_lo = INFINITY, rho_hi = 0, v = 0, g2 = 0;
        const int n = 4000;
        const double h = 1e-4 * T / n;
        for (int i = 0; i <= n; ++i) {
          const double t = T * i / n;
          const double qx = p.qx + p.vx * t + 0.5 * p.ax * t * t,
                       qy = p.qy + p.vy * t + 0.5 * p.ay * t * t;
          rho_lo = std::min(rho_lo, std::hypot(qx, qy)),
          rho_hi = std::max(rho_hi, std::hypot(qx, qy));
          v = std::max(v, std::hypot(p.vx + p.ax * t, p.vy + p.ay * t));
          g2 = std::max(g2, std::abs(rate(p, t + h) - rate(p, t - h)) / (2 * h));
        }
        // Near the tip radius the edge's lag is held (a kink: no bound is claimed), and near the
        // rim the lag's slope grows without one.
        if (rho_lo < 1.2 * tip || rho_hi > 0.9 * R) continue;
        const auto k = shape.over(0.99 * rho_lo, 1.01 * rho_hi);
        const double A = std::hypot(p.ax, p.ay);
        const double bound = topomill::plugins::phase_curvature(k.k1, k.k2, v, A, 0.99 * rho_lo);
        INFO(name << " helix " << helix << (straight ? " straight" : " bent") << ": rho " << rho_lo
                  << " .. " << rho_hi << " mm, v " << v << " mm/s, A " << A
                  << " mm/s^2: sampled |G''| " << g2 << ", bound " << bound);
        CHECK(g2 <= bound * (1 + 1e-6));
        if (straight && helix == 0) CHECK(bound <= 1.6 * g2);
      }
    }
  }
}

// phase_range: G over a piece from its ends' values and rates and |G''| <= c. Against functions
// whose |G''| is at most c, sampled densely (among them caps that peak inside the piece, which
// the ends alone would miss): every sample within the range. And it is the tightest such bound:
// a cap of curvature c meets it at its peak, a bowl at its bottom.
TEST_CASE("phase curvature: the range from the ends holds G and is met by a cap",
          "[tooth_passage]") {
  using topomill::plugins::phase_range;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int q = 0; q < 2000; ++q) {
    const double h = 1e-3 * (1 + std::abs(unit(rng))), c = 1e5 * (0.1 + std::abs(unit(rng)));
    // G(s) = g0 + r s + a sin(k s + phi) + b s^2 / 2, |G''| <= a k^2 + |b| <= c.
    const double share = std::abs(unit(rng)), k = 3000 * std::abs(unit(rng)) + 1;
    const double a = share * c / (k * k), b = (1 - share) * c * unit(rng);
    const double g0 = unit(rng), r = 500 * unit(rng), phi = 3 * unit(rng);
    auto G = [&](double s) { return g0 + r * s + a * std::sin(k * s + phi) + 0.5 * b * s * s; };
    auto dG = [&](double s) { return r + a * k * std::cos(k * s + phi) + b * s; };
    const auto [lo, hi] = phase_range(G(0), G(h), dG(0), dG(h), c, h);
    double g_lo = INFINITY, g_hi = -INFINITY;
    for (int i = 0; i <= 2000; ++i) {
      const double g = G(h * i / 2000);
      g_lo = std::min(g_lo, g), g_hi = std::max(g_hi, g);
    }
    INFO("piece " << q << ": sampled [" << g_lo << ", " << g_hi << "], range [" << lo << ", " << hi
                  << "]");
    CHECK(lo <= g_lo + 1e-12);
    CHECK(g_hi <= hi + 1e-12);
  }
  // The extremal functions: G'' = +-c switched twice (bang-bang), which come closest to the bound.
  for (int q = 0; q < 2000; ++q) {
    const double h = 1e-3, c = 1e5 * (0.1 + std::abs(unit(rng)));
    const int n = 2000;
    int s1 = static_cast<int>(n * std::abs(unit(rng))),
        s2 = static_cast<int>(n * std::abs(unit(rng)));
    if (s1 > s2) std::swap(s1, s2);
    const double sign = unit(rng) < 0 ? -1.0 : 1.0, dt = h / n;
    double g = unit(rng), r = 300 * unit(rng);
    const double ga = g, ra = r;
    double g_lo = g, g_hi = g;
    for (int i = 0; i < n; ++i) {
      const double a = (i < s1 || i >= s2 ? sign : -sign) * c;
      g += r * dt + 0.5 * a * dt * dt, r += a * dt;
      g_lo = std::min(g_lo, g), g_hi = std::max(g_hi, g);
    }
    const auto [lo, hi] = phase_range(ga, g, ra, r, c, h);
    INFO("bang-bang " << q << ": sampled [" << g_lo << ", " << g_hi << "], range [" << lo << ", "
                      << hi << "]");
    CHECK(lo <= g_lo + 1e-12);
    CHECK(g_hi <= hi + 1e-12);
  }
  const double h = 2e-3, c = 4e5;
  for (const double s0 : {0.3e-3, 1e-3, 1.6e-3, 2.5e-3}) {
    // A cap of curvature c peaking at s0 (inside but the last): its top exactly the peak, its
    // bottom exactly the lower end; the bowl that mirrors it, the same mirrored.
    auto G = [&](double s) { return 0.7 - 0.5 * c * (s - s0) * (s - s0); };
    auto dG = [&](double s) { return -c * (s - s0); };
    const double peak = s0 < h ? 0.7 : G(h);
    const auto [lo, hi] = phase_range(G(0), G(h), dG(0), dG(h), c, h);
    INFO("cap at " << s0 << ": range [" << lo << ", " << hi << "]");
    CHECK(std::abs(hi - peak) < 1e-12);
    CHECK(std::abs(lo - std::min(G(0), G(h))) < 1e-12);
    const auto [lo2, hi2] = phase_range(-G(0), -G(h), -dG(0), -dG(h), c, h);
    CHECK(std::abs(hi2 + lo) < 1e-12);
    CHECK(std::abs(lo2 + hi) < 1e-12);
  }
}
