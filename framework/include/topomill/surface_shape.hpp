// Slot: the nominal (uncut) workpiece surface (docs/model.md Eq. 8-12).
#pragma once

#include <limits>

#include "topomill/model.hpp"

namespace topomill {

// A cylindrical surface with its axis along X: its cross-section in the Y-Z plane is a curve
// z = height(y). The outward normal is (0, sin lambda, cos lambda), lambda measured from +Z
// towards +Y. All lengths in mm, angles in rad.
class TOPOMILL_API SurfaceShape : public Model {
 public:
  virtual double height(double y) const = 0;       // v(y)
  virtual double inclination(double y) const = 0;  // lambda(y)
  // The y of the surface point whose normal is at `lambda`; throws ParamError if none exists.
  virtual double y_at_inclination(double lambda) const = 0;
  // Signed curvature radius: > 0 convex, < 0 concave, +infinity for a plane (CATW, Eq. 39-42).
  virtual double curvature_radius() const = 0;
  // Signed distance of the point (y, z), along the surface normal, from the nominal surface moved
  // inward by `depth` (the nominal cut surface): the residual height of form removal (Fig. 10).
  virtual double normal_residual(double y, double z, double depth) const = 0;
  // Arc-length coordinate s of the foot point of (y, z) on the surface, to unroll the surface.
  virtual double arc_coordinate(double y, double z) const = 0;
  // The y interval on which the surface exists (an arc ends where its normal turns horizontal).
  virtual double y_min() const { return -std::numeric_limits<double>::infinity(); }
  virtual double y_max() const { return std::numeric_limits<double>::infinity(); }

  static constexpr double kFlat = std::numeric_limits<double>::infinity();
};

template <>
struct SlotOf<SurfaceShape> {
  static constexpr Slot value = Slot::SurfaceShape;
};

}  // namespace topomill
