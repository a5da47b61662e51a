// A bound of the phase's second derivative |G''| over a piece of a pass, from the path of the
// point over the node (its distance rho from the axis at least rho_lo, its speed at most v, its
// acceleration at most `accel`) and the lag's slope and bend in u = ln(rho) there (LagShape's
// k1, k2). The exact windows prove the phase monotone on a piece from its rates at the ends and
// this bound (PassageGeometry::crossings_in).
//
// With q the point's offset from the axis, D = q . q', M = q x q' (so D^2 + M^2 = rho^2 v^2):
// G' = omega + Psi_u u' - az', u' = D / rho^2, az' = M / rho^2, and
// G'' = Psi_uu u'^2 + [Psi_u (M^2 - D^2) + 2 M D] / rho^4 + (Psi_u q . q'' - q x q'') / rho^2
// (D' = |q'|^2 + q . q'', M' = q x q''). The bracket is the real and imaginary parts of
// (D + i M)^2 taken with (-Psi_u, 1), so at most S rho^2 v^2, S = sqrt(1 + Psi_u^2); the last
// term likewise at most S rho |q''|. Hence
// |G''| <= (k2 + S) v^2 / rho_lo^2 + S accel / rho_lo: for a straight pass at distance d with no
// lag, v^2 / d^2, where the true largest is 0.65 v^2 / d^2 (at 0.58 d either side of the closest
// approach). tests/plugins/phase_curvature_test.cpp samples G'' along random paths against it.
#pragma once

#include <cmath>

namespace topomill::plugins {

inline double phase_curvature(double k1, double k2, double v, double accel, double rho_lo) {
  const double S = std::sqrt(1 + k1 * k1), speed = v / rho_lo;
  return (k2 + S) * speed * speed + S * accel / rho_lo;
}

}  // namespace topomill::plugins
