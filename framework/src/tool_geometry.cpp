#include "topomill/tool_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace topomill {

double ToolGeometry::tooth_angle(int tooth) const {
  return 2.0 * M_PI * static_cast<double>(tooth) / static_cast<double>(teeth());
}

double ToolGeometry::lag_sc(double sin_alpha, double cos_alpha) const {
  return lag(std::atan2(sin_alpha, cos_alpha));
}

double ToolGeometry::lag_slope_sc(double sin_alpha, double cos_alpha) const {
  return lag_slope(std::atan2(sin_alpha, cos_alpha));
}

Vec2 ToolGeometry::section(double alpha) const {
  const double r = radius();
  return {ring() + r * std::sin(alpha), -r * std::cos(alpha)};
}

Vec3 ToolGeometry::edge_point(int tooth, double alpha, double spindle_angle) const {
  const double phi = tooth_angle(tooth) + lag(std::max(alpha, min_polar_angle())) + spindle_angle;
  const Vec2 s = section(alpha);
  return {s.x() * std::cos(phi), s.x() * std::sin(phi), s.y()};
}

Vec3 ToolGeometry::bottom_point(int tooth, double rho, double spindle_angle) const {
  const double phi = tooth_angle(tooth) + lag(std::max(0.0, min_polar_angle())) + spindle_angle;
  return {rho * std::cos(phi), rho * std::sin(phi), section(0.0).y()};
}

}  // namespace topomill
