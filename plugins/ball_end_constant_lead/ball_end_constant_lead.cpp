// Lee and Altintas (1996) ball-end edge: constant lead, the edge advances tan(gamma) R of lag per
// R of axial height, as the shank's helix does.
#include <cmath>

#include "../common/ball_end.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Measured like the loxodrome (zero lag at the shank, alpha = pi/2, growing towards the tip) the
// lag is Psi = tan(gamma) cos(alpha): the axial height above the tip over R times tan(gamma), less
// its shank value. docs/model.md writes tan(gamma)(1 - cos alpha), which is the same curve measured
// from the tip and wound the other way; its own check value (32.6 deg at alpha = 10 deg, gamma = 30
// deg) is this form's. Finite at the tip: nothing singular to handle.
class BallEndConstantLead : public BallEnd {
 public:
  static Schema schema() { return base_schema(); }
  explicit BallEndConstantLead(const Params& p) : BallEnd(p) {}

  double lag(double alpha) const override { return tan_helix_ * std::cos(alpha); }
  double lag_sc(double, double cos_alpha) const override { return tan_helix_ * cos_alpha; }
  double lag_slope(double alpha) const override { return -tan_helix_ * std::sin(alpha); }
  double lag_slope_sc(double sin_alpha, double) const override { return -tan_helix_ * sin_alpha; }
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("ball_end_constant_lead", "0.1.0") {
  registrar.add<topomill::ToolGeometry, topomill::plugins::BallEndConstantLead>(
      "ball_end_constant_lead",
      "Ball-end mill with a constant-lead edge, Psi = tan(gamma) cos(alpha) (Lee-Altintas)");
}
