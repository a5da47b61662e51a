// Every crossing in [a, b] on a window whose centre keeps to its line (PassageGeometry::lined():
// a vertical tool on a fixed frame, an ideal pass, the node off the line's strip), found directly
// instead of by halving (crossings_in).
//
// The phase's rate is G' = omega - Psi_u D / rho^2 + M / rho^2, with q = node - centre,
// v = centre', D = q . v, M = q x v, rho = |q| and Psi_u = dPsi / d ln(rho) (rate()). Times
// rho^2 it is K = omega rho^2 - Psi_u D + M, whose sign is G''s and which has no pole at the axis.
// With a = v', j = a' (the table's cubics), D' = -|v|^2 + q . a, D'' = -3 v . a + q . j,
// M' = q x a, M'' = -v x a + q x j, u = ln(rho), u' = -D / rho^2 and
// u'' = -D' / rho^2 - 2 D^2 / rho^4:
//   K'  = -2 omega D + Psi_uu D^2 / rho^2 - Psi_u D' + M'
//   K'' = 2 omega |v|^2 - 2 omega q . a - Psi_u'' D - 2 Psi_u' D' - Psi_u D'' + M''
// with Psi_u' = Psi_uu u', Psi_u'' = Psi_uuu u'^2 + Psi_uu u''. With |v| within [V_lo, V],
// |a| <= A, |j| <= J, rho within [rho_lo, rho_hi] and the lag's derivatives in ln(rho) at most
// k1, k2, k3 (LagShape) there, K'' in the spindle's sense is at least
//   m = 2 |omega| V_lo^2 - 2 |omega| rho_hi A - (k3 + 5 k2) V^3 / rho_lo - 3 k2 V A
//       - (1 + 3 k1) V A - (1 + k1) rho_hi J.
// Where m > 0, F = sign(omega) K is convex over [a, b], so it has at most two zeros: a falling
// one t1, where the phase turns back against the spindle, and a rising one t2, where it turns on
// again. On a straight pass at constant speed m is 2 |omega| V^2 less the lag's bends, and K a
// parabola in t for a lag of constant slope: the loxodrome's tip, or no lag.
//
// The zeros are found by steps from the ends inwards. K'' >= m gives F a parabola below it at
// every point t: F(x) >= F(t) + F'(t) (x - t) + m (x - t)^2 / 2, with F'(t) known but for the
// lag's bend (Psi_uu within +-k2) and taken at its steepest towards the zero. Each step goes to
// that parabola's nearer zero, which never lies past F's; where the parabola has no zero ahead, F
// has none on the rest of [a, b]. On a straight pass m is F'' but for the lag's bends, and two
// steps mostly settle a zero: a step ends about F / |F'| before it, over which the phase turns
// by at most about F^2 / (|F'| rho^2), and under 1e-13 rad (the phase's round-off) that is taken
// as the turning point. Between the turning points G is monotone, its turn across each piece is
// advance()'s (exact: the centre keeps to a strip that leaves the node out), and every tooth's
// levels are solved in their brackets by Newton's steps on G' = K / rho^2, started where the
// row's last node had its crossings (hints), nearest the envelope's bottom first, until a
// crossing is as high as the lowest found.
//
// The table's cubics meet with jumps of their derivatives of round-off size (none on a line at
// constant speed); F is convex piece by piece and continuous to round-off, as the spans take it.
// Measured on the paper's lambda 0 patch (0.3 mm at 1 um): 13.6 k zones, 11.7 k of them with two
// turning points; a zone takes 5.7 evaluations of K for its turning points, a probe at each end
// and turning point, and 3.2 evaluations and probes for each level solved (0.48 a zone), against
// 7.9 pieces (a span and a probe each) by halving (CHANGELOG.md).
#include <algorithm>
#include <array>
#include <cmath>

#include "passage_geometry.hpp"

namespace topomill::plugins {

double PassageGeometry::lined_convexity(double rho_hi, double* k2) const {
  if (!lined() || !(rho_hi < rim())) return -INFINITY;
  const PassageSetup::PlanLine& line = s_.window[win_].plan_line;
  const double w = std::abs(s_.omega), rho_lo = line_gap_;
  const LagShape::Bound k = s_.lag_shape.over(rho_lo, rho_hi);
  const double k3 = s_.lag_shape.bend_rate_to(rho_hi);
  if (k.kink || !std::isfinite(k3)) return -INFINITY;
  if (k2) *k2 = k.k2;
  const double V = line.speed_hi, A = table_.accel_xy(), J = table_.jerk_xy();
  return 2 * w * line.along_lo * line.along_lo - 2 * w * rho_hi * A -
         (k3 + 5 * k.k2) * V * V * V / rho_lo - 3 * k.k2 * V * A - (1 + 3 * k.k1) * V * A -
         (1 + k.k1) * rho_hi * J;
}

// One call's direct zone: F = sign(omega) K at a time, the range [lo, hi] of its slope and the
// envelope's slope (the ball's height over the node), the steps to F's zeros, and each level's
// solve on a monotone piece.
struct PassageGeometry::LinedZone {
  struct Eval {
    double t, f, lo, hi, rise, r2;
    Vec3 c;  // the centre
  };
  const PassageGeometry& geo;
  const double sense, k2;  // the spindle's sense; the lag's bend as the convexity bound took it
  const std::vector<Hint>* hints;

  // (Out of line: it has five call sites, which inlined would spread the zone over more of the
  // instruction cache than its work needs.)
  [[gnu::noinline]] bool eval(double t, Eval& e) const {
    const PassageSetup& s = geo.s_;
    Vec3 c, v, acc;
    if (!geo.table_.nominal_jet(t, c, v, acc)) return false;
    const double qx = geo.x_ - c.x(), qy = geo.y_ - c.y(), r2 = qx * qx + qy * qy;
    const double D = qx * v.x() + qy * v.y(), M = qx * v.y() - qy * v.x();
    double psi, rise;
    if (s.ringed) {
      // The hull's rise: its depth (flat inside the ring) falls at its slope times rho', rho' =
      // -D / rho; on a split side the inner side's too.
      const double rho = std::sqrt(r2);
      const CutterProfile::Point p = s.profile.at(rho);
      psi = s.profile.slope(*s.tool, rho, p);
      const double out = rho - s.profile.ring();
      rise = v.z() - ((out > 0 || geo.split()) && p.on ? p.steep * D / rho : 0.0);
    } else {
      const double sin_a = std::sqrt(r2) / s.R, cos_a = std::sqrt(1 - sin_a * sin_a);
      psi = s.lag_shape.slope(sin_a, cos_a, *s.tool);
      rise = v.z() - D / (s.R * cos_a);
    }
    const double dD = qx * acc.x() + qy * acc.y() - (v.x() * v.x() + v.y() * v.y());
    const double slope = sense * (-2 * s.omega * D - psi * dD + (qx * acc.y() - qy * acc.x()));
    const double bend = k2 * D * D / r2;  // |Psi_uu D^2 / rho^2|
    e = {t, sense * (s.omega * r2 - psi * D + M), slope - bend, slope + bend, rise, r2, c};
    return true;
  }
  // A step ends about F / |F'| before its zero; over that the phase turns by at most about
  // F^2 / (|F'| rho^2) past its turning point, and under 1e-13 rad (the phase's round-off) it is
  // taken as the zero.
  static bool settled(double f, double steep, double r2) {
    return steep > 0 && f * f <= 1e-13 * steep * r2;
  }
  // Steps from e (an end, where F > 0) towards the other end `far` (dir 1 from the start, -1 from
  // the end), each to the nearer zero of the parabola that bounds F from below: F(x) >= F(t) +
  // F'(t) (x - t) + m (x - t)^2 / 2, with F'(t) taken at its steepest towards the zero. A parabola
  // of no zero before the far end proves F positive on the rest: `none`. False where the steps do
  // not settle (a near touch: crossings_in) or leave the table.
  bool step_to_zero(Eval& e, double far, int dir, double m, bool& zero, bool& none) const {
    for (int it = 0; e.f > 0 && !zero && !none; ++it) {
      const double slope = dir > 0 ? e.lo : e.hi, s = dir * slope, disc = s * s - 2 * m * e.f;
      const double step = s < 0 && disc >= 0 ? 2 * e.f / (std::sqrt(disc) - s) : INFINITY;
      if (!(dir * (e.t + dir * step) < dir * far)) {
        none = true;
      } else {
        if (it == 40) return false;
        if (!eval(e.t + dir * step, e)) return false;
        zero = e.f <= 0 || settled(e.f, dir > 0 ? -e.hi : e.lo, e.r2);
      }
    }
    return true;
  }
  // Where G (unwrapped from probe q0 at t0) equals `level` on a monotone piece [t0, t1], G(t1) =
  // g1: Newton's steps on G' = K / rho^2 (eval), kept within the bracket (else its middle), to
  // |G - level| < 1e-9 rad as crossing() converges; `out` gets tooth 0's probe there. (Regula
  // falsi takes about nine probes a level next to a turning point, where G is a parabola.)
  double solve(int tooth, double level, double t0, const Probe& q0, double t1, const Probe& q1,
               double g1, Probe& out) const {
    double b_lo = t0, b_hi = t1, f_lo = q0.g - level;
    if (f_lo == 0 || g1 == level) return out = f_lo == 0 ? q0 : q1, f_lo == 0 ? t0 : t1;
    double t = b_lo + (b_hi - b_lo) * f_lo / (f_lo - (g1 - level));
    if (hints) {
      double near = INFINITY;
      for (const Hint& h : *hints)
        if (h.tooth == tooth && h.t > t0 && h.t < t1 && std::abs(h.t - t) < near)
          near = std::abs(h.t - t), t = h.t;
    }
    for (int it = 0; it < 100; ++it) {
      Eval e{};
      if (!eval(t, e)) e.c = geo.table_(t), e.f = NAN;  // (never within [a, b]: ends were read)
      out = geo.probe(0, t, e.c);
      const double f = q0.g + geo.advance(t0, q0, t, out) - level;
      if (std::abs(f) < 1e-9 || b_hi - b_lo <= 1e-13 * geo.s_.rev) break;
      if ((f < 0) == (f_lo < 0))
        b_lo = t, f_lo = f;
      else
        b_hi = t;
      const double next = t - f * e.r2 / (sense * e.f);
      t = next > b_lo && next < b_hi ? next : 0.5 * (b_lo + b_hi);
    }
    return t;
  }
};

bool PassageGeometry::crossings_lined(int only, double a, double b, double& below,
                                      std::vector<Crossing>& roots, Probe* ends,
                                      const std::vector<Hint>* hints) const {
  if (!lined() || !(b > a)) return false;
  const PassageSetup::PlanLine& line = s_.window[win_].plan_line;
  const double sense = s_.omega > 0 ? 1.0 : -1.0;
  const Probe pa = probe(0, a), pb = probe(0, b);
  // The node's distance from the axis over [a, b]: at least its distance from the line's strip
  // (lined_convexity's rho_lo); at most its distance across from the strip's far side together with
  // the larger at the ends (the centre moves forwards along the line, so its offset along stays
  // within the ends').
  const double rho_hi = std::hypot(std::max(pa.rho, pb.rho), line_gap_ + 2 * line.off);
  double k2 = 0;  // the lag's bend there, as m takes it
  const double m = lined_convexity(rho_hi, &k2);
  if (!(m > 0)) return false;

  using Eval = LinedZone::Eval;
  const LinedZone zone{*this, sense, k2, hints};
  Eval lo{}, hi{};
  if (!zone.eval(a, lo) || !zone.eval(b, hi)) return false;
  const Eval at_a = lo, at_b = hi;
  // Steps inwards from each end where F > 0 there (see above) to F's zeros, the phase's turning
  // points (a near touch that does not settle: crossings_in).
  bool zero_lo = false, zero_hi = false, none = false;
  if (!zone.step_to_zero(lo, b, 1, m, zero_lo, none)) return false;
  if (!zone.step_to_zero(hi, a, -1, m, zero_hi, none)) return false;
  // The monotone pieces: [a, t1], [t1, t2], [t2, b], those that exist.
  std::array<Eval, 4> cut;
  std::array<Probe, 4> q;
  std::size_t n = 0;
  cut[n] = at_a, q[n++] = pa;
  if (zero_lo && lo.t > a && lo.t < b) cut[n] = lo, q[n] = probe(0, lo.t), ++n;
  if (zero_hi && hi.t > cut[n - 1].t && hi.t < b) cut[n] = hi, q[n] = probe(0, hi.t), ++n;
  cut[n] = at_b, q[n++] = pb;
  const int first = only < 0 ? 0 : only, last = only < 0 ? s_.teeth - 1 : only;
  auto offset = [&](int j) { return s_.tooth_angle[j] - s_.tooth_angle[0]; };
  // Each piece's phase at its end, unwrapped from its start (advance), and how many levels it
  // passes: more than `levels` holds (a whole revolution passes two per tooth) goes to
  // crossings_in, before anything is found.
  std::array<double, 4> g_end{};
  struct Level {
    int tooth;
    double g;
  };
  std::array<Level, 64> levels;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    g_end[i] = q[i].g + advance(cut[i].t, q[i], cut[i + 1].t, q[i + 1]);
    const double v_lo = std::min(q[i].g, g_end[i]), v_hi = std::max(q[i].g, g_end[i]);
    if ((v_hi - v_lo) / kTwoPi + 1 > static_cast<double>(levels.size()) / (last - first + 1))
      return false;
  }
  if (ends) ends[0] = pa, ends[1] = pb;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eval &e0 = cut[i], &e1 = cut[i + 1];
    const Probe& q0 = q[i];
    const double g0 = q0.g, g1 = g_end[i];
    // The ball rises away from the envelope's bottom (it has one): from the start on where it
    // rises there, towards the start where it falls at the end. Past a crossing as high as the
    // lowest found, every later one is higher.
    const bool rising = e0.rise >= 0, falling = !rising && e1.rise <= 0;
    if ((rising && q0.height >= below) || (falling && q[i + 1].height >= below)) continue;
    std::size_t count = 0;
    const double v_lo = std::min(g0, g1), v_hi = std::max(g0, g1);
    for (int j = first; j <= last; ++j)
      for (double mm = std::ceil((v_lo + offset(j)) / kTwoPi); mm * kTwoPi - offset(j) <= v_hi;
           ++mm)
        levels[count++] = {j, mm * kTwoPi - offset(j)};
    // In time order from the end the heights rise from (G rises with time where g1 >= g0).
    const bool ascending = (g1 >= g0) != falling;
    std::sort(
        levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(count),
        [ascending](const Level& x, const Level& y) { return ascending ? x.g < y.g : x.g > y.g; });
    for (std::size_t l = 0; l < count; ++l) {
      Probe p0;
      const double t = zone.solve(levels[l].tooth, levels[l].g, e0.t, q0, e1.t, q[i + 1], g1, p0);
      const Probe p = turned_to(p0, levels[l].tooth);
      roots.push_back({levels[l].tooth, t, p});
      if (p.over) below = std::min(below, p.height);
      if ((rising || falling) && p.height >= below) break;
    }
  }
  return true;
}

}  // namespace topomill::plugins
