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
// approach). tests/plugins/tooth_passage/phase_curvature_test.cpp samples G'' along random paths
// against it.
//
// The same bound C limits how far G can stray over a piece of length h from its values and rates
// at the ends (phase_range). Between its ends G is highest at an end or at a peak s inside, where
// G'(s) = 0: G' comes down from G'_a to 0 by s, so s >= |G'_a| / C, and on [0, s]
// G' <= min(G'_a + C u, C (s - u)), whose integral bounds G(s) - G_a (peak_from: quadratic in s and
// rising); from the right end likewise (falling in s). Their difference is linear in s: they
// meet at one s, which bounds the peak exactly, or where that lies outside the peak's possible
// places, the nearer of those does. A cap of curvature C meets the bound at its top
// (tests/plugins/tooth_passage/phase_curvature_test.cpp). Near a turn-back of the phase, where no
// monotone proof exists, a piece whose range holds no crossing level is then settled without
// halving (crossings_in).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

namespace topomill::plugins {

inline double phase_curvature(double k1, double k2, double v, double accel, double rho_lo) {
  const double S = std::sqrt(1 + k1 * k1), speed = v / rho_lo;
  return (k2 + S) * speed * speed + S * accel / rho_lo;
}

// The highest G can be at a peak s (G'(s) = 0) from G(0) = g, G'(0) = r and |G''| <= c, for
// |r| <= c s: the integral of min(r + c u, c (s - u)) over [0, s], the two lines meeting inside.
inline double peak_from(double g, double r, double c, double s) {
  return g + s * (0.25 * c * s + 0.5 * r) - 0.25 * r * r / c;
}

// Bounds [lo, hi] of G over [0, h] from G(0) = ga, G(h) = gb, G'(0) = ra, G'(h) = rb and
// |G''| <= c there (see above).
inline std::pair<double, double> phase_range(double ga, double gb, double ra, double rb, double c,
                                             double h) {
  auto top = [h, c](double g0, double g1, double r0, double r1) {
    double best = std::max(g0, g1);
    // Where a peak can be: G' down to 0 from r0 by s, and from 0 to r1 after it.
    const double lo = std::abs(r0) / c, hi = h - std::abs(r1) / c;
    if (lo <= hi) {
      // peak_from(g0, r0, c, s) - peak_from(g1, -r1, c, h - s) = k0 + k1 s, k1 >= 0 (as
      // |r1 - r0| <= c h): rising less falling, so the lower of the two is largest where they
      // meet, or at the end of [lo, hi] nearer to it.
      const double k1 = 0.5 * (c * h + r0 - r1);
      const double k0 = g0 - g1 - 0.25 * c * h * h + 0.25 * (r1 * r1 - r0 * r0) / c + 0.5 * r1 * h;
      const double s = std::clamp(k1 > 0 ? -k0 / k1 : 0.5 * (lo + hi), lo, hi);
      best = std::max(best, std::min(peak_from(g0, r0, c, s), peak_from(g1, -r1, c, h - s)));
    }
    return best;
  };
  return {-top(-ga, -gb, -ra, -rb), top(ga, gb, ra, rb)};
}

}  // namespace topomill::plugins
