// From a scene's region and cutting tables to the node grid, and through the path model to the
// tool path (docs/model.md Eq. 13-16), checked to stay on the workpiece's surface.
#pragma once

#include <memory>

#include "scene.hpp"
#include "topomill/path_model.hpp"
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
                   std::shared_ptr<const SurfaceShape> surface, const PathModel& path_model);

}  // namespace topomill
