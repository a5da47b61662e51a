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

Vec3 ToolGeometry::edge_point(int tooth, double alpha, double spindle_angle) const {
  const double r = radius();
  const double phi = tooth_angle(tooth) + lag(std::max(alpha, min_polar_angle())) + spindle_angle;
  const double s = std::sin(alpha);
  return {r * s * std::cos(phi), r * s * std::sin(phi), -r * std::cos(alpha)};
}

}  // namespace topomill
