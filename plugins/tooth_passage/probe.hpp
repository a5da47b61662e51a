// What one probe of a tooth's edge over a node reads: whether the edge is there, its phase, and
// the ball's height.
#pragma once

namespace topomill::plugins {

struct Probe {
  bool over;      // under the ball, inside the contact range
  double g;       // edge azimuth minus node azimuth, wrapped
  double height;  // ball height above the node (+inf when not under the ball)
  double rho;     // distance from the axis
  double lag;     // the edge's lag at rho (NaN when not under the ball)
};

}  // namespace topomill::plugins
