// Slot: the cutting edges of a ball-end mill (docs/model.md Eq. 1-5).
#pragma once

#include "topomill/model.hpp"
#include "topomill/types.hpp"

namespace topomill {

// Edges are curves on the ball of radius R, parameterised by the polar angle alpha measured from
// the tip (alpha = 0) to the shank (alpha = pi/2). Tool frame CS1: origin at the ball centre,
// Z up along the spindle, so the tip is at z = -R.
class TOPOMILL_API ToolGeometry : public Model {
 public:
  virtual double radius() const = 0;  // R, mm
  virtual int teeth() const = 0;      // N
  // Lag angle Psi(alpha) (rad) of the edge behind its shank end, and its derivative.
  virtual double lag(double alpha) const = 0;
  virtual double lag_slope(double alpha) const = 0;
  // The lag from sin(alpha) and cos(alpha), for callers that have them and not alpha (a node
  // under the ball gives both from a square root; asin would cost more than the rest).
  // Override with a closed form where one exists; must agree with lag(alpha).
  virtual double lag_sc(double sin_alpha, double cos_alpha) const;
  // The same for lag_slope (the force model needs it per edge element and sample).
  virtual double lag_slope_sc(double sin_alpha, double cos_alpha) const;
  // Smallest polar angle at which the edge may be evaluated (rad). An edge whose lag is singular
  // at the tip (the loxodrome) returns a positive value; callers treat [0, min) as the tip point.
  virtual double min_polar_angle() const { return 0.0; }

  // Angular position of tooth j (0-based) at spindle angle 0: theta_j = 2 pi j / N (Eq. 4).
  double tooth_angle(int tooth) const;
  // Edge point of tooth j at polar angle alpha when the spindle has turned by `spindle_angle`
  // (rad, positive about +Z), in CS1 (Eq. 1, 5-7). Below min_polar_angle() the lag is held at
  // its value there, so the edge runs on to the tip point without winding infinitely.
  Vec3 edge_point(int tooth, double alpha, double spindle_angle) const;
};

template <>
struct SlotOf<ToolGeometry> {
  static constexpr Slot value = Slot::ToolGeometry;
};

}  // namespace topomill
