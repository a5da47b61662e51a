// What both ball-end edge models share: radius, teeth and helix angle, and their schema.
#pragma once

#include <cmath>

#include "cutter_schema.hpp"
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
    add_teeth(s);
    add_helix(s, "Helix angle gamma where the edge meets the shank");
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
