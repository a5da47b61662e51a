// Slot: the cutting edges of a milling cutter (docs/model.md Eq. 1-5, "Cutters").
#pragma once

#include "topomill/model.hpp"
#include "topomill/types.hpp"

namespace topomill {

// Every cutter is a solid of revolution about its axis, and its edges lie on that solid's lower
// part: a tube of radius r = radius() whose centre runs round a circle of radius c = ring() in
// the plane z = 0 of the tool frame CS1 (Z up along the spindle). c = 0 is the ball end (the
// paper's); a bull-nose has c = D/2 - r and a flat bottom at z = -r inside the ring, and a flat
// end is a bull-nose with a small or zero corner radius; a round-insert face mill has c = D/2
// and edges round the tube's lower half on both sides of the ring.
//
// The edges on the tube are parameterised by the polar angle alpha of the tube's section,
// measured from its lowest point (alpha = 0) outwards to the side (alpha = pi/2), and inwards
// (negative) for an insert. On a ball it is the paper's polar angle from the tip.
class TOPOMILL_API ToolGeometry : public Model {
 public:
  virtual double radius() const = 0;  // r (R for a ball), mm
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

  // The ring c (mm): 0 for a ball end.
  virtual double ring() const { return 0.0; }
  // Where the edge on the tube starts (rad): 0 for an end mill (its end edge, if any, runs on
  // inside the ring on the flat bottom), -pi/2 at most for an insert cutting on both sides.
  virtual double first_polar_angle() const { return 0.0; }
  // Whether edges run over the flat bottom inside the ring (an end mill with c > 0), radially,
  // at the lag they have at alpha = 0.
  bool has_bottom() const { return ring() > 0 && first_polar_angle() == 0; }
  // The edge's section at alpha: distance from the axis and height in CS1. By default the tube's
  // circle, (c + r sin alpha, -r cos alpha); an insert tilted by an axial rake overrides it.
  virtual Vec2 section(double alpha) const;
  // How far the edges reach from the axis (mm): by default the section at alpha = pi/2; a section
  // that folds back before it (an insert with a negative axial rake) overrides this.
  virtual double reach() const { return section(M_PI / 2).x(); }
  // An end mill's side edge, on the cylinder of radius reach() above the tube's centre plane: its
  // lag falls by side_lead() rad per mm of height from lag(pi/2) (tan(helix) / (D/2)).
  virtual double side_lead() const { return 0.0; }

  // Angular position of tooth j (0-based) at spindle angle 0: theta_j = 2 pi j / N (Eq. 4).
  double tooth_angle(int tooth) const;
  // Edge point of tooth j at polar angle alpha when the spindle has turned by `spindle_angle`
  // (rad, positive about +Z), in CS1 (Eq. 1, 5-7). Below min_polar_angle() the lag is held at
  // its value there, so the edge runs on to the tip point without winding infinitely.
  Vec3 edge_point(int tooth, double alpha, double spindle_angle) const;
  // Edge point of tooth j on the flat bottom at distance rho < ring() from the axis.
  Vec3 bottom_point(int tooth, double rho, double spindle_angle) const;
};

template <>
struct SlotOf<ToolGeometry> {
  static constexpr Slot value = Slot::ToolGeometry;
};

}  // namespace topomill
