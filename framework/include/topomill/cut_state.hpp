// What force and deformation models need to know about the tool at one instant.
#pragma once

#include <functional>

#include "topomill/types.hpp"

namespace topomill {

struct CutState {
  double time = 0.0;             // s
  double spindle_angle = 0.0;    // rad, positive about +Z
  Vec3 feed_direction{0, 1, 0};  // unit vector in CS2 (tangent to the surface along the pass)
  double feed_per_tooth = 0.0;   // fz, mm
  // Engaged range of the edge's polar angle (CATW), rad; for a cutter with a ring, its whole edge
  // (the CATW is the ball's), with in_material telling what cuts.
  double alpha_min = 0.0;
  double alpha_max = 0.0;
  double inclination = 0.0;   // lambda of the surface under the tool, rad
  double spindle_rate = 0.0;  // rad/s, signed: > 0 counter-clockwise seen from above
  double depth_of_cut = 0.0;  // ap, mm
  double stepover = 0.0;      // ae, mm
  // Whether a point at `offset` (mm, CS2) from the ball centre is still workpiece material: below
  // the uncut surface and outside what the previous pass removed. Set by the core; empty means
  // "every point of the CATW", as in the paper's Eq. 21.
  std::function<bool(const Vec3& offset)> in_material;
  // Radial runout (ToolPath::Runout): the ball centre `runout` mm off the spindle axis towards
  // spindle_angle + runout_angle. Each tooth's reach then differs from the one before it, and
  // so its chip (the force model's business; the path already carries the offset).
  double runout = 0.0;        // mm
  double runout_angle = 0.0;  // rad
  // Per-edge runout (ToolPath::Runout): edge K is K edge_radial farther out, K edge_axial higher.
  double edge_radial = 0.0, edge_axial = 0.0;  // mm
};

// Resultant cutting force on the tool (N, CS2) and the load centre: the force-weighted mean
// distance (mm) of the engaged elements from the tool tip along the axis (Eq. 28).
struct CuttingForce {
  Vec3 force = Vec3::Zero();
  double load_centre = 0.0;
};

}  // namespace topomill
