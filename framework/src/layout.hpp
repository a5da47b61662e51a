// From a scene's region, cutting and path tables to the node grid and the raster tool path
// (docs/model.md Eq. 13-16): enough passes and feed length before and after the patch that every node
// of it is finished.
#pragma once

#include <memory>

#include "scene.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/tool_geometry.hpp"
#include "topomill/tool_path.hpp"

namespace topomill {

struct Layout {
  Grid grid;                  // Z-map nodes over the XY projection of the patch
  double s_lo = 0, s_hi = 0;  // arc-length extent of the patch along the surface (mm)
  double spacing = 0;         // requested node spacing on the surface (mm)
  double kappa = 0;           // CATW half-width (rad)
  double lambda_max = 0;      // largest |lambda| under the tool along the path (rad)
  std::shared_ptr<ToolPath> path;
};

// Throws InputError (naming the scene key) for geometry the model cannot represent.
Layout make_layout(const Scene& scene, const ToolGeometry& tool,
                   std::shared_ptr<const SurfaceShape> surface);

// The y whose surface point has arc coordinate s (bisection; arc_coordinate grows with y).
double y_at_arc(const SurfaceShape& surface, double s, double y_guess, double span);

}  // namespace topomill
