// PassageGeometry's bottom of a bound along a window: a golden section, and the reference's
// window about a level time. Included by passage_geometry.hpp.
#pragma once

#include "passage_geometry.hpp"

namespace topomill::plugins {

template <class F>
double PassageGeometry::bottom(F f, double a, double b) const {
  const double lo = a, hi = b, ratio = 0.5 * (std::sqrt(5.0) - 1);
  double u = b - ratio * (b - a), v = a + ratio * (b - a), fu = f(u), fv = f(v);
  while (b - a > kBottomTolerance * s_.period) {
    if (fu < fv)
      b = v, v = u, fv = fu, u = b - ratio * (b - a), fu = f(u);
    else
      a = u, u = v, fu = fv, v = a + ratio * (b - a), fv = f(v);
  }
  const double mid = 0.5 * (a + b), f_mid = f(mid);
  if (a == lo && f(lo) < f_mid) return lo;
  if (b == hi && f(hi) < f_mid) return hi;
  return mid;
}

template <class F>
double PassageGeometry::bottom_near(F f, double t0) const {
  const double span = 2 * s_.profile.reach() / s_.speed;
  const double t = bottom(f, std::max(t_lo_, t0 - span), std::min(t_hi_, t0 + span));
  return s_.ringed && within(t0) && f(t0) <= f(t) ? t0 : t;
}

}  // namespace topomill::plugins
