// A worn ball-end mill: flank wear takes `wear` off the radius of the cutting edge, which keeps
// the paper's loxodromic lag. The model is a header so that the plugin and its test share it.
#pragma once

#include <cmath>

#include "topomill/error.hpp"
#include "topomill/params.hpp"
#include "topomill/tool_geometry.hpp"

namespace worn {

class BallEndWorn : public topomill::ToolGeometry {
 public:
  // The schema is data: the scene loader checks the scene's [tool] table against it before this
  // class is constructed, and `topomill describe ball_end_worn` prints it.
  static topomill::Schema schema() {
    topomill::Schema s;
    s.add_number("radius", "Nominal ball radius R").with_unit("mm").above(0).is_required();
    s.add_number("wear", "Radial flank wear taken off the edge")
        .with_unit("mm")
        .at_least(0)
        .with_default(0.0);
    s.add_integer("teeth", "Number of teeth").at_least(1).at_most(16).with_default(std::int64_t{2});
    s.add_number("helix_angle", "Helix angle")
        .with_unit("deg")
        .at_least(0)
        .below(90)
        .with_default(30.0);
    return s;
  }

  explicit BallEndWorn(const topomill::Params& p)
      : radius_(p.number("radius") - p.number("wear")),
        teeth_(static_cast<int>(p.integer("teeth"))),
        tan_helix_(std::tan(p.number("helix_angle") * M_PI / 180)) {
    // What a schema cannot say: a ParamError names the key, and topomill reports it at the
    // scene's file and line.
    if (radius_ <= 0)
      throw topomill::ParamError("wear", "the wear must be smaller than the radius");
  }

  double radius() const override { return radius_; }
  int teeth() const override { return teeth_; }
  double lag(double a) const override { return tan_helix_ * std::log(1 / std::tan(a / 2)); }
  double lag_slope(double a) const override { return -tan_helix_ / std::sin(a); }
  double min_polar_angle() const override { return 1e-4; }  // the loxodrome's tip singularity

 private:
  double radius_;
  int teeth_;
  double tan_helix_;
};

}  // namespace worn
