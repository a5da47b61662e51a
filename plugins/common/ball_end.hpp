// What both ball-end edge models share: radius, teeth and helix angle, and their schema.
#pragma once

#include <cmath>

#include "topomill/params.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class BallEnd : public ToolGeometry {
 public:
  static Schema base_schema() {
    Schema s;
    s.add_number("radius", "Ball radius R (up to 1 m: beyond, no tool)")
        .with_unit("mm")
        .above(0)
        .at_most(1000)
        .is_required();
    s.add_integer("teeth", "Number of teeth N, evenly spaced")
        .at_least(1)
        .at_most(64)
        .with_default(std::int64_t{2});
    s.add_number("helix_angle", "Helix angle gamma where the edge meets the shank")
        .with_unit("deg")
        .at_least(0)
        .below(90)
        .with_default(30.0);
    return s;
  }

  explicit BallEnd(const Params& p)
      : radius_(p.number("radius")),
        teeth_(static_cast<int>(p.integer("teeth"))),
        tan_helix_(std::tan(p.number("helix_angle") * M_PI / 180.0)) {}

  double radius() const override { return radius_; }
  int teeth() const override { return teeth_; }

 protected:
  double radius_;
  int teeth_;
  double tan_helix_;
};

}  // namespace topomill::plugins
