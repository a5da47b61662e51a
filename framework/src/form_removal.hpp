// Form removal of a simulated map: the residual height along the surface normal from the nominal
// cut surface, unrolled onto a uniform (x, s) grid, s the arc length (the paper's Fig. 10).
#pragma once

#include "topomill/surface_shape.hpp"
#include "topomill/types.hpp"

namespace topomill {

// `raw` on the Z-map grid (heights in mm). The result has nodes x as `raw` and s from s_lo to s_hi
// with the spacing of x nearest to `spacing`; heights in mm. Each column is interpolated
// linearly in s between the Z-map's nodes.
HeightMap unroll_residual(const HeightMap& raw, const SurfaceShape& surface, double depth,
                          double s_lo, double s_hi, double spacing);

}  // namespace topomill
