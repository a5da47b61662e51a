// What bounds the phase's turn over a piece [a, b] of a window at one node
// (PassageGeometry::span): the node's distance from the axis, the phase's rate in the spindle's
// sense, its curvature, and what the lag and the azimuth can turn it by.
#pragma once

#include <algorithm>
#include <cmath>

namespace topomill::plugins {

struct PhaseSpan {
  double rho_lo, rho_hi;  // the node's least and greatest distance from the axis
  // G the unwrapped phase, G' = dG/dt: in the spindle's sense, within [w - fall, w + rise]
  // (w = |omega|).
  double fall, rise;
  double curve;  // |G''| <= curve; +inf where G' may jump (a knot, the tip radius)
  // Next to the rim the lag's rate has no bound: fall and rise then leave the lag out, and
  // `jump` bounds how far it turns the phase over the piece (LagShape::variation); else 0.
  double jump = 0;
  // The node's least distance from the centre in plan, for the ball's height (rho_lo but for
  // a tilted tool, whose rho is the ball point's distance from its own axis).
  double plan_lo = 0;
  // How far the lag and the azimuth can turn the phase over the piece together, from the
  // length of the moving point's path (the integral of |G' - w| <= S |v| / rho): where a
  // correction's jerk makes the top speed, and so fall and rise, large, one fast piece of it
  // moves the point only by its own length. +inf where the length is not known.
  double sweep = INFINITY;
  // The correction's lowest height over the piece, where span() read its box (a knot inside):
  // with the nominal centre's lowest, the ball's floor there (crossings_in asks for it only
  // where the piece's phase can reach a crossing). NaN when not read.
  double box_z_lo = NAN;
  // The sense G keeps all along by these bounds: +1 with the spindle (G' >= w - fall > 0), -1
  // against it (G' <= w + rise < 0: where the axis passes close on the side where the node's
  // azimuth turns against the spindle faster than it, G falls by about pi and crosses a level
  // between three times), 0 where either may hold.
  int sense(double w) const {
    if (jump != 0) return 0;
    if (fall < w) return 1;
    return w + rise < 0 ? -1 : 0;
  }
  double top(double w) const { return std::max(w + rise, fall - w); }  // |G'| <= top
  // |G(b) - G(a)| over a piece of length h = b - a.
  double turn(double w, double h) const { return std::min(top(w) * h, w * h + sweep) + jump; }
};

}  // namespace topomill::plugins
