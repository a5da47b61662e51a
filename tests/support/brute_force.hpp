// The lowest edge height over a node, by brute force: every pass, every tooth, the time the ball
// can be below the uncut surface sampled finely (finer near the axis, where the node's azimuth
// turns at v / rho), the edge taken from ToolGeometry::edge_point (docs/model.md Eq. 1-7, not an
// evaluator's own formula), every sign change of the edge-minus-node azimuth bisected. No bound,
// no stopping rule. Used by the near-axis and the kinematics tests.
#pragma once

#include "topomill/tool_geometry.hpp"
#include "topomill/tool_path.hpp"

namespace testing {
// The lowest edge height over (x, y) on the run's (corrected) path, or the uncut surface.
double brute_force_height(const topomill::ToolGeometry& tool, const topomill::ToolPath& path,
                          double x, double y);
}  // namespace testing
