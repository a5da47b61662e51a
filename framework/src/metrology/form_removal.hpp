// Form removal, measured and simulated: least-squares fits of measured surfaces (plane,
// polynomial of total order N, and an arc: a cylinder with its axis along X, convex or concave,
// over the valid points), and a simulated map's residual from the nominal cut surface.
#pragma once

#include <string>

#include "metrology/surface.hpp"
#include "topomill/surface_shape.hpp"

namespace topomill {

struct Form {
  enum class Kind { None, Plane, Polynomial, Arc } kind = Kind::None;
  int order = 1;  // Polynomial

  // "none", "plane", "poly:N" (N = 1..6), "arc"; throws InputError naming `option` otherwise.
  static Form parse(const std::string& text, const std::string& option);
  std::string name() const;
};

// The residual heights (mm): the map minus the fitted form; for the arc, the signed distance from
// the fitted circle along its radius (outward positive). Invalid points stay as they are.
Surface remove_form(const Surface& surface, const Form& form);

// A simulated map's residual height along the surface normal from the nominal cut surface (the
// workpiece `depth` below its uncut face), unrolled onto a uniform (x, s) grid, s the arc length
// (the paper's Fig. 10). `raw` on the Z-map grid (heights in mm). The result has nodes x as `raw`
// and s from s_lo to s_hi with the spacing of x nearest to `spacing`; heights in mm. Each column
// is interpolated linearly in s between the Z-map's nodes.
HeightMap unroll_residual(const HeightMap& raw, const SurfaceShape& surface, double depth,
                          double s_lo, double s_hi, double spacing);

}  // namespace topomill
