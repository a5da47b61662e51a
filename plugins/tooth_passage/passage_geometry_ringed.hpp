// PassageGeometry's probe of a ringed cutter (a vertical axis): the cutter's profile over the node
// (cutter_profile.hpp) where the ball's probe has the sphere. Included by passage_geometry.hpp.
#pragma once

#include "passage_geometry.hpp"

namespace topomill::plugins {

inline Probe PassageGeometry::probe_ringed(int tooth, double t, const Vec3& c) const {
  const double dx = x_ - c.x(), dy = y_ - c.y(), rho = norm(dx, dy);
  const CutterProfile& f = s_.profile;
  const CutterProfile::Point p = f.at(rho);
  const double lag = f.lag(*s_.tool, rho, p);
  return {p.on && rho >= rho_lo_ && rho <= rho_hi_, phase(tooth, t, lag, dx, dy),
          p.on ? c.z() - p.depth + f.up() : INFINITY, rho, lag};
}

}  // namespace topomill::plugins
