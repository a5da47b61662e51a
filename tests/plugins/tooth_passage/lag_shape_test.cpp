// tooth_passage's bounds of the edge's lag (LagShape): over any range of distances from the
// tool's axis, the largest slope of the lag in ln(rho) and how far the lag turns, which bound
// the phase's rate and turn in every span (PassageGeometry::bound_rates). Checked against the
// tool's own lag, differenced here on a fine grid in ln(rho): the table's bound must hold it
// (a bound that is too low lets the walks skip a crossing), and stay within the table's own
// margin of the largest from the axis out to the range's end, which is what it keeps (for the
// built-in edges, whose slope grows outwards, the range's own): a bound that is far too high
// only slows them, but says the table reads the wrong bins.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <random>

#include "support/builtin_models.hpp"
#include "tooth_passage/lag_shape.hpp"

using testing::make_model;
using topomill::ToolGeometry;

namespace {
// An edge whose lag's slope is not monotone in rho, as neither built-in edge's is: the largest
// slope over a range then lies inside it, not at an end, which the table must find.
class WavyEdge : public ToolGeometry {
 public:
  double radius() const override { return 5.0; }
  int teeth() const override { return 2; }
  double lag(double alpha) const override { return 0.3 * std::sin(20 * alpha); }
  double lag_slope(double alpha) const override { return 6 * std::cos(20 * alpha); }
};
}  // namespace

TEST_CASE("lag shape: the slope bound over any range of distances holds the lag's own slope",
          "[tooth_passage]") {
  for (const std::string name : {"ball_end_loxodrome", "ball_end_constant_lead", "wavy"}) {
    const std::shared_ptr<ToolGeometry> tool =
        name == "wavy" ? std::make_shared<WavyEdge>()
                       : make_model<ToolGeometry>(name, {{"radius", 5}, {"helix_angle", 30}});
    const topomill::plugins::LagShape shape(*tool);
    const double R = tool->radius(), tip = R * std::sin(tool->min_polar_angle());
    // The lag at rho (held below the tip radius, as the edge holds it).
    auto lag = [&](double rho) {
      const double s = std::max(rho, tip) / R;
      return tool->lag_sc(s, std::sqrt(1 - s * s));
    };
    // The largest |dPsi / d ln rho| over [lo, hi] by differences on 400 steps in ln(rho), and
    // the lag's largest change between two points of the range.
    auto sampled = [&](double lo, double hi, double& slope, double& turn) {
      slope = 0;
      double psi_lo = INFINITY, psi_hi = -INFINITY;
      const double u0 = std::log(lo), u1 = std::log(hi);
      const int n = 400;
      for (int i = 0; i <= n; ++i) {
        const double u = u0 + (u1 - u0) * i / n, rho = std::exp(u), psi = lag(rho);
        psi_lo = std::min(psi_lo, psi), psi_hi = std::max(psi_hi, psi);
        const double e = 1e-6;
        if (rho * std::exp(e) < R && rho * std::exp(-e) > tip)
          slope =
              std::max(slope, std::abs(lag(rho * std::exp(e)) - lag(rho * std::exp(-e))) / (2 * e));
      }
      turn = psi_hi - psi_lo;
    };
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int q = 0; q < 300; ++q) {
      // Ranges from a micrometre to most of the ball, log-uniform, short and long.
      const double lo = 1e-3 * std::pow(0.9 * R / 1e-3, unit(rng));
      const double hi = std::min(0.95 * R, lo * std::pow(q % 2 ? 1.05 : 20.0, unit(rng)));
      if (!(hi > lo)) continue;
      double slope = 0, turn = 0;
      sampled(lo, hi, slope, turn);
      const auto bound = shape.over(lo, hi);
      INFO(name << " over [" << lo << ", " << hi << "] mm: sampled slope " << slope << ", bound "
                << bound.k1 << "; lag turns " << turn << ", bound " << shape.variation(lo, hi));
      CHECK(bound.k1 >= slope * (1 - 1e-6));
      CHECK(shape.variation(lo, hi) >= turn * (1 - 1e-6));
      // The bins' samples widened by 10 %, over at most one more bin at each end (R / 4096):
      // within a fifth of the slope a little beyond the range. The bound is the largest from
      // the axis out to hi (what slope_to gives, and monotony and next_gap ask), sampled
      // from a micrometre out (below it the three edges' slopes are held, constant or
      // vanishing): for the built-in edges, whose slope grows outwards, that is the range's own.
      double wide = 0, unused = 0, from_axis = 0;
      sampled(std::max(lo - 2 * R / 4096, 1e-4), std::min(hi + 2 * R / 4096, 0.99 * R), wide,
              unused);
      sampled(1e-3, hi, from_axis, unused);
      INFO("from the axis to " << hi << " mm: sampled " << from_axis << ", slope_to "
                               << shape.slope_to(hi));
      CHECK(shape.slope_to(hi) == bound.k1);
      CHECK(bound.k1 >= from_axis * (1 - 1e-6));
      CHECK(bound.k1 <= 1.2 * std::max(from_axis, wide) + 1e-9);
      if (name != "wavy") CHECK(bound.k1 <= 1.2 * wide + 1e-9);
      // The bend d^2 Psi / d (ln rho)^2 from the axis out to hi (which land() asks), sampled by
      // second differences on the same steps (where the lag is not held).
      double bend = 0;
      for (int i = 0; i <= 400; ++i) {
        const double rho = std::exp(std::log(1e-3) + (std::log(hi) - std::log(1e-3)) * i / 400);
        const double e = 1e-4;
        if (rho * std::exp(e) < R && rho * std::exp(-e) > tip)
          bend = std::max(
              bend,
              std::abs(lag(rho * std::exp(e)) - 2 * lag(rho) + lag(rho * std::exp(-e))) / (e * e));
      }
      INFO("bend sampled " << bend << ", bound " << bound.k2);
      CHECK(bound.k2 >= bend * (1 - 1e-3) - 1e-6);  // (round-off in the differences)
    }
  }
}
