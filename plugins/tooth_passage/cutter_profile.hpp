// The cutter's lower surface over a node, for a vertical axis, as a function of the node's
// distance rho from the axis: the tube of radius r on the ring c (ToolGeometry), its flat bottom
// inside the ring where the cutter has one, and how far up one edge sits (per-edge runout). On a
// ball (c = 0) it is the sphere the walks were written for; PassageGeometry keeps the sphere's own
// expressions there, and reads this profile for a cutter with a ring.
//
// Over a node at rho the tube's section gives e = rho - c = r sin(alpha) and a depth
// sqrt(r^2 - e^2) below the tube's centre plane; the bottom (e < 0 on an end mill) is r deep, and
// an insert's inner side (e < 0 without a bottom) is the tube's too. The edge's lag is a function
// of alpha, held below the tip radius (the bottom, or the loxodrome's tip) and constant where no
// edge is (an insert's hole, inside the ring of a ball whose edge a per-edge runout moved out), so
// that the phase stays continuous for the walks' bounds.
//
// The walks bound a pass by an envelope with a single minimum: the depth is continued as the
// tube's deepest, r, everywhere inside the ring (the *hull*: on the insert's inner side and its
// hole deeper than the cutter is, so a true lower bound) and, past the reach, rising at the rim's
// slope 1 (as the sphere's is continued).
#pragma once

#include <algorithm>
#include <cmath>

#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class CutterProfile {
 public:
  // The tool's own profile, its ring moved out by `out` and raised by `up` (an edge's per-edge
  // runout: ToolPath::Runout).
  explicit CutterProfile(const ToolGeometry& tool, double out = 0.0, double up = 0.0)
      : r_(tool.radius()),
        c_(tool.ring() + out),
        up_(up),
        bottom_(tool.has_bottom()),
        inner_(tool.first_polar_angle() < 0),
        start_(inner_    ? std::max(0.0, c_ + r_ * std::sin(tool.first_polar_angle()))
               : bottom_ ? out
                         : c_),
        tip_(inner_ ? start_ : c_ + r_ * std::sin(tool.min_polar_angle())),
        lag_tip_(tool.lag(inner_ ? tool.first_polar_angle() : tool.min_polar_angle())),
        lag_rim_(tool.lag_sc(1.0, 0.0)) {}

  // Whether the tool's section is the tube's circle, which the profile describes (ToolGeometry's
  // default): an insert tilted by an axial rake has another.
  static bool describes(const ToolGeometry& tool) {
    constexpr int kSamples = 16;
    const double r = tool.radius(), c = tool.ring(), a0 = tool.first_polar_angle();
    for (int k = 0; k <= kSamples; ++k) {
      const double a = a0 + (M_PI / 2 - a0) * k / kSamples;
      const Vec2 p = tool.section(a);
      if (std::abs(p.x() - (c + r * std::sin(a))) > 1e-12 * (c + r) ||
          std::abs(p.y() + r * std::cos(a)) > 1e-12 * (c + r))
        return false;
    }
    return true;
  }

  double tube() const { return r_; }
  double ring() const { return c_; }
  double up() const { return up_; }
  // How far the edges reach from the axis, and the nearest they come to it.
  double reach() const { return c_ + r_; }
  double start() const { return start_; }
  // Below this distance the lag is held at lag_tip().
  double tip() const { return tip_; }
  double lag_tip() const { return lag_tip_; }
  bool ringed() const { return c_ > 0; }
  // Whether the surface is its hull (below) wherever the hull is within the reach: the ball, and
  // an end mill whose bottom reaches the axis. Elsewhere (an insert's inner side and hole, an edge
  // a per-edge runout moved off the axis) the heights along a pass may have two minima.
  bool surface_is_hull() const { return !ringed() || (bottom_ && start_ == 0); }
  // Whether, without a bottom, the depth on the tube's two sides is the surface wherever an edge
  // is: then on either side of the axis's closest approach to a node (the distance monotone) the
  // heights have one minimum, and split_depth() bounds them (an insert, a ball's edge moved out).
  bool splits() const { return ringed() && !bottom_; }

  // The surface over a node at rho: whether an edge is there, its depth below the tube's centre
  // plane, and the section's sin and cos of alpha (0 and 1 on the bottom).
  struct Point {
    bool on;
    double depth, sin_a, cos_a;
  };
  Point at(double rho) const {
    const double e = rho - c_;
    if (e < 0 && bottom_) return {rho >= start_, r_, 0.0, 1.0};
    const double s = e / r_;
    if (!(std::abs(s) < 1) || rho < start_) return {false, 0.0, s < 0 ? -1.0 : 1.0, 0.0};
    const double cos_a = std::sqrt(1 - s * s);
    return {true, r_ * cos_a, s, cos_a};
  }
  // The edge's lag at a point: held below the tip radius, and beyond the reach at the rim's, so
  // that the phase there goes on continuously (the walks' bounds and turns read it across).
  double lag(const ToolGeometry& tool, double rho, const Point& p) const {
    if (rho >= reach()) return lag_rim_;
    return rho < tip_ || !p.on ? lag_tip_ : tool.lag_sc(p.sin_a, p.cos_a);
  }
  // dPsi / d ln(rho) there: rho Psi'(alpha) / (r cos alpha); zero where the lag is held.
  double slope(const ToolGeometry& tool, double rho, const Point& p) const {
    if (rho < tip_ || !p.on) return 0.0;
    const double d = tool.lag_slope_sc(p.sin_a, p.cos_a);
    return d == 0 ? 0.0 : rho * d / (r_ * p.cos_a);
  }

  // The hull's depth at rho (see above): non-increasing in rho, continuous, at least the cutter's;
  // so also the deepest it is over all distances from rho out.
  double hull_depth(double rho) const {
    const double e = rho - c_;
    if (e <= 0) return r_;
    const double s = e / r_;  // (as at() takes it: the same bits where both apply)
    return s < 1 ? r_ * std::sqrt(1 - s * s) : r_ - e;
  }
  // The tube's depth continued past both rims, falling at slope 1 (the sphere's continuation):
  // the surface's where an edge is, below it (above the cutter) elsewhere, and unimodal in rho.
  double split_depth(double rho) const {
    const double e = rho - c_, s = e / r_;
    return std::abs(s) < 1 ? r_ * std::sqrt(1 - s * s) : r_ - std::abs(e);
  }

  // How far out the lag's slope and the height's are bounded: a fraction of the tube's radius
  // beyond its centre (an insert's inner side needs no such limit: its lag is constant, and the
  // walks bound its height by the split depth, not its slope).
  double rim_out(double fraction) const { return c_ + fraction * r_; }
  // The steepest the surface's height is over rho within [lo, hi] (tan of alpha: 0 on the
  // bottom), given both within the rims.
  double steepest(double lo, double hi) const { return std::max(steepness(lo), steepness(hi)); }

 private:
  double steepness(double rho) const {
    const double e = rho - c_;
    if (e <= 0 && bottom_) return 0.0;
    const double s = std::min(std::abs(e) / r_, 1.0);
    return s / std::sqrt(1 - s * s);
  }

  double r_, c_, up_;
  bool bottom_, inner_;
  double start_, tip_, lag_tip_, lag_rim_;
};

}  // namespace topomill::plugins
