// The paper's ball-end edge (Eq. 1-3): a loxodrome, constant helix angle everywhere on the ball.
#include <cmath>

#include "../common/ball_end.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Psi(alpha) = tan(gamma) ln(cot(alpha / 2)) grows without bound at the tip: the edge winds
// infinitely often around it while its radius R sin(alpha) shrinks to zero. Below `tip_angle`
// the lag is held constant (ToolGeometry::edge_point), i.e. the last bit of edge runs straight
// to the tip point. With the default 0.01 deg that bit lies within R sin(0.01 deg) = 0.9 um of
// the axis for R = 5 mm, below any grid this program is used with.
class BallEndLoxodrome : public BallEnd {
 public:
  static Schema schema() {
    Schema s = base_schema();
    s.add_number("tip_angle",
                 "Polar angle below which the lag is held constant (the tip singularity)")
        .with_unit("deg")
        .above(0)
        .below(90)
        .with_default(0.01);
    return s;
  }
  explicit BallEndLoxodrome(const Params& p)
      : BallEnd(p), tip_angle_(p.number("tip_angle") * M_PI / 180.0) {}

  double lag(double alpha) const override {
    return tan_helix_ * std::log(1.0 / std::tan(0.5 * alpha));
  }
  // cot(alpha / 2) = (1 + cos alpha) / sin alpha: no tan, no asin.
  double lag_sc(double sin_alpha, double cos_alpha) const override {
    return tan_helix_ * std::log((1.0 + cos_alpha) / sin_alpha);
  }
  double lag_slope(double alpha) const override { return -tan_helix_ / std::sin(alpha); }
  double lag_slope_sc(double sin_alpha, double) const override { return -tan_helix_ / sin_alpha; }
  double min_polar_angle() const override { return tip_angle_; }

 private:
  double tip_angle_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("ball_end_loxodrome", "0.1.0") {
  registrar.add<topomill::ToolGeometry, topomill::plugins::BallEndLoxodrome>(
      "ball_end_loxodrome",
      "Ball-end mill with a loxodromic edge, constant helix angle (Hao et al. Eq. 1-3)");
}
