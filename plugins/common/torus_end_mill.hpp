// What the bull-nose and the flat end share: an end mill of diameter D whose corner is a quarter
// of a tube of radius r centred on the ring c = D/2 - r, a flat bottom inside the ring, and a
// constant-lead edge (docs/model.md, "Cutters").
#pragma once

#include <cmath>

#include "cutter_schema.hpp"
#include "topomill/error.hpp"
#include "topomill/params.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class TorusEndMill : public ToolGeometry {
 public:
  static Schema base_schema() {
    Schema s;
    s.add_number("diameter", "Cutter diameter D (up to 2 m: beyond, no tool)")
        .with_unit("mm")
        .above(0)
        .at_most(2000)
        .is_required();
    add_teeth(s);
    add_helix(s, "Helix angle gamma of the side edge, which the corner continues");
    return s;
  }

  // `corner` is r; the caller's schema bounds it below, and here it is held within D/2.
  TorusEndMill(const Params& p, double corner)
      : half_(p.number("diameter") / 2),
        corner_(corner),
        teeth_(static_cast<int>(p.integer("teeth"))),
        // The side edge winds tan(gamma) / (D/2) per mm of height; the corner's edge keeps that
        // lead, and is r cos(alpha) above the tube's centre plane at alpha.
        side_(std::tan(p.number("helix_angle") * M_PI / 180.0) / half_),
        lead_(std::tan(p.number("helix_angle") * M_PI / 180.0) * (corner / half_)) {
    if (corner > half_)
      throw ParamError("corner_radius",
                       "the corner radius is more than half the diameter: expected at most D/2 "
                       "(D/2 is the ball end)");
  }

  double radius() const override { return corner_; }
  int teeth() const override { return teeth_; }
  // D/2 - r: zero, to the bit, when r = D/2 (the ball end).
  double ring() const override { return half_ - corner_; }
  // Psi = lead r cos(alpha) / (D/2): zero at the shank, the constant-lead ball's when r = D/2.
  double lag(double alpha) const override { return lead_ * std::cos(alpha); }
  double lag_sc(double, double cos_alpha) const override { return lead_ * cos_alpha; }
  double lag_slope(double alpha) const override { return -lead_ * std::sin(alpha); }
  double lag_slope_sc(double sin_alpha, double) const override { return -lead_ * sin_alpha; }
  double side_lead() const override { return side_; }

 private:
  double half_, corner_;
  int teeth_;
  double side_, lead_;
};

}  // namespace topomill::plugins
