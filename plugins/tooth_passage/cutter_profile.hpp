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
// An insert tilted by an axial rake gamma_p (sp, cp its sine and cosine) has the circle sheared in
// its plane: in units of r, X = (rho - c) / r = u + w sp and Z = w cp above the lowest point, with
// u = sin(alpha), w = 1 - cos(alpha) (round_insert.cpp). Eliminating alpha, (1 + sp^2) Z^2 -
// 2 cp (1 + X sp) Z + cp^2 X^2 = 0, an ellipse; the surface is its lower root,
//   Z = cp X^2 / (1 + X sp + q),  q = sqrt(1 + 2 X sp - X^2) = dX/dalpha,
// its slope dZ/dX = cp u / q. The edge folds back where q = 0 (the ellipse's widest, X = sp +-
// sqrt(1
// + sp^2)): outwards for sp < 0, inwards for sp > 0; what lies past a fold is above the lower root
// and never the surface. With sp = 0 all of this is the circle (the circle's own expressions are
// kept there, to the bit).
//
// The walks bound a pass by an envelope with a single minimum: the depth is continued as the
// tube's deepest, r, everywhere inside the ring (the *hull*: on the insert's inner side and its
// hole deeper than the cutter is, so a true lower bound) and, past the section's widest, rising at
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
        sp_(rake(tool).sin_p),
        cp_(rake(tool).cos_p),
        raked_(sp_ != 0.0),
        bottom_(tool.has_bottom()),
        inner_(tool.first_polar_angle() < 0),
        x_hi_(sp_ < 0 ? sp_ + std::sqrt(1 + sp_ * sp_) : 1.0 + sp_),
        start_(inner_    ? std::max(0.0, c_ + r_ * inner_end(tool.first_polar_angle()))
               : bottom_ ? out
                         : c_),
        tip_(inner_ ? start_ : c_ + r_ * std::sin(tool.min_polar_angle())),
        lag_tip_(tool.lag(inner_ ? tool.first_polar_angle() : tool.min_polar_angle())),
        lag_rim_(tool.lag_sc(1.0, 0.0)) {}

  // Whether the tool's section is the tube's circle, sheared by an axial rake or not, which the
  // profile describes (every cutter topomill has).
  static bool describes(const ToolGeometry& tool) {
    constexpr int kSamples = 16;
    const double r = tool.radius(), c = tool.ring(), a0 = tool.first_polar_angle();
    const Rake k = rake(tool);
    for (int i = 0; i <= kSamples; ++i) {
      const double a = a0 + (M_PI / 2 - a0) * i / kSamples, w = 1 - std::cos(a);
      const Vec2 p = tool.section(a);
      if (std::abs(p.x() - (c + r * (std::sin(a) + w * k.sin_p))) > 1e-12 * (c + r) ||
          std::abs(p.y() - r * (w * k.cos_p - 1)) > 1e-12 * (c + r))
        return false;
    }
    return true;
  }

  double tube() const { return r_; }
  double ring() const { return c_; }
  double up() const { return up_; }
  // How far the edges reach from the axis (the section's widest), and the nearest they come to it.
  double reach() const { return c_ + r_ * x_hi_; }
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
  // plane, the section's sin and cos of alpha (0 and 1 on the bottom), dX/dalpha there (cos(alpha)
  // on the circle) and the height's slope in rho (tan(alpha) on the circle).
  struct Point {
    bool on;
    double depth, sin_a, cos_a, dx, steep;
  };
  Point at(double rho) const {
    if (raked_) return sheared_at(rho);
    const double e = rho - c_;
    if (e < 0 && bottom_) return {rho >= start_, r_, 0.0, 1.0, 1.0, 0.0};
    const double s = e / r_;
    if (!(std::abs(s) < 1) || rho < start_) return {false, 0.0, s < 0 ? -1.0 : 1.0, 0.0, 0.0, 0.0};
    const double cos_a = std::sqrt(1 - s * s);
    return {true, r_ * cos_a, s, cos_a, cos_a, s / cos_a};
  }
  // The edge's lag at a point: held below the tip radius, and beyond the reach at the rim's, so
  // that the phase there goes on continuously (the walks' bounds and turns read it across).
  double lag(const ToolGeometry& tool, double rho, const Point& p) const {
    if (rho >= reach()) return lag_rim_;
    return rho < tip_ || !p.on ? lag_tip_ : tool.lag_sc(p.sin_a, p.cos_a);
  }
  // dPsi / d ln(rho) there: rho Psi'(alpha) / (r dX/dalpha); zero where the lag is held.
  double slope(const ToolGeometry& tool, double rho, const Point& p) const {
    if (rho < tip_ || !p.on) return 0.0;
    const double d = tool.lag_slope_sc(p.sin_a, p.cos_a);
    return d == 0 ? 0.0 : rho * d / (r_ * p.dx);
  }

  // The hull's depth at rho (see above): non-increasing in rho, continuous, at least the cutter's;
  // so also the deepest it is over all distances from rho out.
  double hull_depth(double rho) const {
    const double e = rho - c_;
    if (e <= 0) return r_;
    if (raked_) return section_depth(e / r_);
    const double s = e / r_;  // (as at() takes it: the same bits where both apply)
    return s < 1 ? r_ * std::sqrt(1 - s * s) : r_ - e;
  }
  // The section's depth continued past its widest on both sides, falling at slope 1 (the
  // sphere's continuation): the surface's where an edge is, below it (above the cutter) elsewhere,
  // and unimodal in rho.
  double split_depth(double rho) const {
    const double e = rho - c_, s = e / r_;
    if (raked_) return section_depth(s);
    return std::abs(s) < 1 ? r_ * std::sqrt(1 - s * s) : r_ - std::abs(e);
  }

  // How far out the lag's slope and the height's are bounded: a fraction of the way from the
  // tube's centre to the reach (an insert's inner side needs no such limit: its lag is constant,
  // and the walks bound its height by the split depth, not its slope).
  double rim_out(double fraction) const { return c_ + fraction * x_hi_ * r_; }
  // The steepest the surface's height is over rho within [lo, hi] (|dZ/dX|: 0 on the bottom),
  // given both within the rims: the lower root is convex, steepest at the ends.
  double steepest(double lo, double hi) const { return std::max(steepness(lo), steepness(hi)); }
  // The surface's |dZ/dX| at rho (0 on the bottom; infinite past the section's widest).
  double steepness(double rho) const {
    const double e = rho - c_;
    if (e <= 0 && bottom_) return 0.0;
    if (raked_) {
      const double s = e / r_;
      const Lower l = lower(s);
      return l.q > 0 ? cp_ * std::abs(s - l.w * sp_) / l.q : INFINITY;
    }
    const double s = std::min(std::abs(e) / r_, 1.0);
    return s / std::sqrt(1 - s * s);
  }
  // The steepest the section is at points `depth` or more below the tube's centre plane, on
  // either side, or past its widest (slope 1): r / depth bounds the circle's tan(alpha).
  double steepest_below(double depth) const {
    if (!(depth > 0)) return INFINITY;
    if (!raked_) return std::max(1.0, r_ / depth);
    // Z = cp (1 - cos(alpha)) there; the steeper side's slope cp |u| / (cos(alpha) - |sp u|).
    const double cos_a = 1 - (1 - depth / r_) / cp_;
    if (cos_a >= 1) return 1.0;
    const double u = std::sqrt(1 - std::min(cos_a * cos_a, 1.0)), q = cos_a - std::abs(sp_) * u;
    return q > 0 && cos_a > 0 ? std::max(1.0, cp_ * u / q) : INFINITY;
  }

 private:
  struct Rake {
    double sin_p, cos_p;
  };
  // The section's rake, from its end at alpha = pi/2 (X = 1 + sp, Z = cp); none on the circle,
  // nor on a sharp corner (r = 0), which is a point.
  static Rake rake(const ToolGeometry& tool) {
    const double r = tool.radius();
    if (!(r > 0)) return {0.0, 1.0};
    const Vec2 rim = tool.section(M_PI / 2);
    const double sin_p = (rim.x() - tool.ring() - r) / r, cos_p = (rim.y() + r) / r;
    if (std::abs(sin_p) < 1e-12 * (1 + tool.ring() / r) && std::abs(cos_p - 1) < 1e-12)
      return {0.0, 1.0};
    return {sin_p, cos_p};
  }
  // at() on a sheared section (an insert has no bottom). Out of line: the probe is the walks' hot
  // path, and its inlining on the circle is what their speed rests on. A fold itself (q = 0, a
  // single distance) counts as no edge, so that the slope stays finite.
  [[gnu::noinline]] Point sheared_at(double rho) const {
    const double s = (rho - c_) / r_;
    const auto [q, w] = lower(s);
    if (!(s < x_hi_) || rho < start_ || !(q > 0))
      return {false, 0.0, s < 0 ? -1.0 : 1.0, 0.0, 0.0, 0.0};
    const double sin_a = s - w * sp_;
    return {true, r_ * (1 - cp_ * w), sin_a, 1 - w, q, cp_ * sin_a / q};
  }
  // The inner end of an insert's edge in units of r, from the ring: its first point's, or the
  // inner fold's (sp > 0) where the edge folds back before it.
  double inner_end(double first) const {
    if (sp_ > 0 && first <= -std::atan(1 / sp_)) return sp_ - std::sqrt(1 + sp_ * sp_);
    return std::sin(first) + (1 - std::cos(first)) * sp_;
  }
  // The raked section's depth at X (units of r from the ring), its lower root within its widest
  // and falling at slope 1 beyond.
  double section_depth(double s) const {
    const double wide = std::sqrt(1 + sp_ * sp_), x = std::clamp(s, sp_ - wide, sp_ + wide);
    return r_ * (1 - cp_ * lower(x).w) - r_ * std::abs(s - x);
  }
  // The lower root at X = s (units of r): q = dX/dalpha (0 at and past the section's widest) and
  // w = 1 - cos(alpha) = Z / cp, written without the cancellation of 1 + X sp - q.
  struct Lower {
    double q, w;
  };
  Lower lower(double s) const {
    const double q = std::sqrt(std::max(0.0, 1 + s * (2 * sp_ - s)));
    return {q, s * s / (1 + s * sp_ + q)};
  }
  double r_, c_, up_, sp_, cp_;
  bool raked_, bottom_, inner_;
  double x_hi_, start_, tip_, lag_tip_, lag_rim_;
};

}  // namespace topomill::plugins
