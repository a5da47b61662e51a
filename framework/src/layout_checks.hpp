// The checks make_layout runs on what it lays out (layout.cpp): the memory the passes take, a
// tilted tool's posture against the cut, and cutter-location data's points against the surface.
#pragma once

#include <string>
#include <vector>

#include "layout.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill {

constexpr double kDeg = M_PI / 180.0;

// A count for a message: three significant digits ("2.6e+06").
std::string format_count(double n);

// The patch in plan, grown by the ball's radius: the points of cutter-location data that can
// cut it.
struct Reach {
  double x_lo, x_hi, y_lo, y_hi;
  bool holds(const Vec3& c) const {
    return c.x() > x_lo && c.x() < x_hi && c.y() > y_lo && c.y() < y_hi;
  }
};

// Refuses a posture whose tool axis leaves the cut outside the ball's lower half.
void check_posture(const ToolPath& path, const ToolGeometry& tool, Layout& L,
                   const SlotTable& slot);
// Refuses a patch whose passes alone would not fit in memory (`steps` step-overs across it).
void check_layout_memory(double steps, double ae, const Params& cut);
// Checks every point of cutter-location data (below); sets L.lambda_max from them.
void check_waypoints(const ToolPath& path, const std::vector<PassLine>& lines, const Reach& reach,
                     const ToolGeometry& tool, Layout& L);

}  // namespace topomill
