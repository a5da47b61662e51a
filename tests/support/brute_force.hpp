// The lowest edge height over a node, by brute force: every pass, every tooth, the time the ball
// can be below the uncut surface sampled finely (finer near the axis, where the node's azimuth
// turns at v / rho), the edge taken from ToolGeometry::edge_point (docs/model.md Eq. 1-7, not an
// evaluator's own formula), every sign change of the edge-minus-node azimuth bisected. The only
// thing left out is time in which the ball's sphere itself stays above the lowest crossing found:
// each 64th of a revolution is bounded by the centre's fastest speed, and revolutions are visited
// lowest bound first. Used by the near-axis, kinematics, runout, CL and posture tests.
//
// A tilted tool (ToolPath::Pass::posture) is followed with a tool frame built here from the
// posture's definition (docs/model.md, "Tool posture"), not from ToolPath::tool_frame: the ball
// point over the node is taken into that frame, and its polar angle there picks the edge point.
#pragma once

#include "topomill/tool_geometry.hpp"
#include "topomill/tool_path.hpp"

namespace testing {
// The lowest edge height over (x, y) on the run's (corrected) path, or the uncut surface.
double brute_force_height(const topomill::ToolGeometry& tool, const topomill::ToolPath& path,
                          double x, double y);

// The tool axis (unit, tip to spindle) on pass p at time t, from the posture's definition: fixed,
// a = cos(tilt) (cos(lead) Z + sin(lead) F) + sin(tilt) C with F the pass's feed in plan and
// C = F x Z; normal, the same about the surface's outward normal n at the contact point, the unit
// feed f along the surface (from the surface's height by a central difference) and c = f x n.
topomill::Vec3 posture_axis(const topomill::ToolPath& path, std::size_t p, double t);
}  // namespace testing
