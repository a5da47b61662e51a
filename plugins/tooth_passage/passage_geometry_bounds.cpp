// PassageGeometry's bounds on the phase's rate over a piece of the window, and what they prove:
// monotone stretches and the least gap to a tooth's next crossing.
#include "passage_geometry.hpp"

#include <algorithm>

#include "phase_curvature.hpp"

namespace topomill::plugins {

// The centre over a piece [a, b] keeps to a convex region in plan (as advance() needs): with no
// correction knot inside, one smooth piece, the (tabulated) centre within A h^2 / 8 of its chord
// (plus round-off) and its speed within A h / 2 of the larger at the ends (the correction's slope
// is one over the piece: the one starting at a, as at b a knot may start the next); with knots
// inside, the nominal centre (within its sagitta of the chord) moved by a correction within the
// box it keeps to over [a, b], so within the chord moved to the box's middle, thickened by the
// sagitta and the box's half diagonal.
PassageGeometry::PlanRegion PassageGeometry::plan_region(const Sample& sa, const Sample& sb,
                                                         const Vec3* na_known,
                                                         const Vec3* nb_known) const {
  const double a = sa.t, b = sb.t, h = b - a;
  const double step = s_.path->correction_step(src_);
  const double A = table_.accel_xy();
  const double first_knot = step > 0 ? std::max(0.0, std::floor(a / step) + 1) * step : INFINITY;
  PlanRegion r;
  r.knot_inside = step > 0 && first_knot < b && first_knot <= last_knot();
  if (!r.knot_inside) {
    r.ca = sa.c, r.cb = sb.c, r.grow = A * h * h / 8 + 1e-12;
    const Vec3 va = sa.v + sa.dv, vb = sb.v + sa.dv;
    r.v = std::max(norm(va.x(), va.y()), norm(vb.x(), vb.y())) + A * h / 2;
  } else {
    const CorrectionBounds box = table_.correction_bounds(a, b);
    const Vec3 &lo = box.lo, &hi = box.hi, mid = 0.5 * (lo + hi);
    const Vec3 na = na_known ? *na_known : table_.nominal(a);
    const Vec3 nb = nb_known ? *nb_known : table_.nominal(b);
    r.ca = na + mid, r.cb = nb + mid;
    r.box_z_lo = lo.z();
    r.grow = A * h * h / 8 + 0.5 * norm(hi.x() - lo.x(), hi.y() - lo.y()) + 1e-12;
    r.v = s_.window[win_].nominal_speed.first + box.speed_xy;
    // The centre's path: the nominal one's at most its top speed a second, the correction's its
    // own pieces' lengths.
    r.length = s_.window[win_].nominal_speed.first * h + table_.correction_length(a, b);
  }
  const Vec3 &ca = r.ca, &cb = r.cb;
  const double u = nearest_on_chord(ca, cb);
  const double ax = x_ - ca.x(), ay = y_ - ca.y(), bx = x_ - cb.x(), by = y_ - cb.y();
  r.lo = std::max(0.0, norm(ax - u * (cb.x() - ca.x()), ay - u * (cb.y() - ca.y())) - r.grow);
  r.hi = std::max(norm(ax, ay), norm(bx, by)) + r.grow;
  return r;
}

// One span for both postures: the plan region first, then the moving point's bounds, the node's
// offset from the axis itself for a vertical tool, its lift into the tool frame for a tilted one.
PassageGeometry::Span PassageGeometry::span(const Sample& sa, const Sample& sb, const Vec3* na,
                                            const Vec3* nb) const {
  const PlanRegion r = plan_region(sa, sb, na, nb);
  Span out = tilted_ ? lifted_rates(sa, sb, r) : plan_rates(sa, sb, r);
  out.plan_lo = r.lo, out.box_z_lo = r.box_z_lo;
  return out;
}

// A vertical tool: the moving point is the node's offset q from the axis, whose distance is the
// region's; its velocity about the node's moment, q x v (whose rate is q x v', as q' = -v), lies
// within rho A h / 2 of the range at the ends on a smooth piece, and within rho_hi v in size
// otherwise.
PassageGeometry::Span PassageGeometry::plan_rates(const Sample& sa, const Sample& sb,
                                                  const PlanRegion& r) const {
  const double A = table_.accel_xy(), h = sb.t - sa.t;
  double c_lo, c_hi;
  if (!r.knot_inside) {
    const Vec3 &ca = r.ca, &cb = r.cb, va = sa.v + sa.dv, vb = sb.v + sa.dv;
    const double ax = x_ - ca.x(), ay = y_ - ca.y(), bx = x_ - cb.x(), by = y_ - cb.y();
    const double m_a = ax * va.y() - ay * va.x(), m_b = bx * vb.y() - by * vb.x();
    const double slack = r.hi * A * h / 2;
    c_lo = std::min(m_a, m_b) - slack, c_hi = std::max(m_a, m_b) + slack;
  } else {
    c_hi = r.hi * r.v, c_lo = -c_hi;
  }
  return bound_rates(r.lo, r.hi, r.v, c_lo, c_hi, A, r.knot_inside, r.length);
}

PassageGeometry::Span PassageGeometry::bound_rates(double rho_lo, double rho_hi, double v,
                                                   double c_lo, double c_hi, double A,
                                                   bool knot_inside, double length) const {
  LagShape::Bound k = s_.lag_shape.over(rho_lo, rho_hi);
  double jump = 0;
  if (!std::isfinite(k.k1)) {  // the rim: the lag's turn, not its rate (lag_shape.hpp)
    jump = s_.lag_shape.variation(rho_lo, rho_hi);
    k = {0, 0, true};  // the rates below without the lag; no curvature bound
  }
  // In u = ln(rho) and the node's azimuth az, G' = omega + Psi_u u' - az' with |u'| <= v / rho
  // and -az' = (q x v) / rho^2; |G''| as phase_curvature.hpp bounds it.
  if (!(rho_lo > 0)) return {rho_lo, rho_hi, INFINITY, INFINITY, INFINITY, jump};
  const double speed = v / rho_lo, lag = k.k1 * speed;
  // -az' within [m_lo, m_hi]: on the side of the pass where the node's azimuth turns with the
  // spindle it only adds to the rate, and only the lag can slow it.
  const double r2_lo = rho_lo * rho_lo, r2_hi = rho_hi * rho_hi;
  const double m_lo = c_lo / (c_lo < 0 ? r2_lo : r2_hi), m_hi = c_hi / (c_hi > 0 ? r2_lo : r2_hi);
  const bool forward = s_.omega > 0;
  double fall = lag - (forward ? m_lo : -m_hi), rise = lag + (forward ? m_hi : -m_lo);
  // The lag's and the azimuth's parts together, (Psi_u (q . q') - q x q') / rho^2, are also at
  // most sqrt(1 + Psi_u^2) v / rho ((q . q', q x q') has length rho v): tighter where the axis
  // passes closest, for an edge that lags (the loxodrome's log spiral).
  const double S = std::sqrt(1 + k.k1 * k.k1), both = S * speed;
  fall = std::min(fall, both), rise = std::min(rise, both);
  // Where the moment keeps one sign, tighter still: with theta the angle from q to v, 1 / rho =
  // |v| sin(theta) / (q x v), so G' - omega = (q x v - Psi_u q . v) / rho^2 = |v|^2 / (q x v)
  // sin(theta) (sin(theta) - Psi_u cos(theta)), whose last part lies within (1 -+ S) / 2. On the
  // side where the azimuth turns with the spindle the lag then slows the phase by at most
  // v^2 (S - 1) / (2 q x v): for a straight pass at distance d, 0.077 v / d at a 30 deg helix
  // (against S v / d = 1.15 v / d from the bound above), and 0 for an edge with no lag at the tip.
  if (c_lo > 0 || c_hi < 0) {
    const double scale = v * v / (c_lo > 0 ? c_lo : -c_hi);
    const double lo = 0.5 * (c_lo > 0 ? 1 - S : -1 - S) * scale;  // G' - omega >= lo
    const double hi = 0.5 * (c_lo > 0 ? 1 + S : S - 1) * scale;   // G' - omega <= hi
    fall = std::min(fall, forward ? -lo : hi), rise = std::min(rise, forward ? hi : -lo);
  }
  const double curve =
      !knot_inside && !k.kink ? phase_curvature(k.k1, k.k2, v, A, rho_lo) : INFINITY;
  auto finite = [](double x) { return std::isnan(x) ? INFINITY : x; };
  Span out{rho_lo, rho_hi, finite(fall), finite(rise), finite(curve), jump};
  if (length < INFINITY)
    out.sweep = S * length / rho_lo;  // at the rim S is 1: the lag's turn is in `jump`
  return out;
}

bool PassageGeometry::lifted(double t, const Vec3& c, const Vec3& v, Vec3& p, Vec3& dp) const {
  const double qx = x_ - c.x(), qy = y_ - c.y(), r2 = qx * qx + qy * qy;
  if (!(r2 < s_.R2)) return false;
  // P = (q, -h), h = sqrt(R^2 - |q|^2); q' = -v, so P' = (-v, -(q . v) / h).
  const double h = std::sqrt(s_.R2 - r2);
  const Vec3 P(qx, qy, -h), dP(-v.x(), -v.y(), -(qx * v.x() + qy * v.y()) / h);
  if (!turning_) {
    p = to_tool_ * P, dp = to_tool_ * dP;
    return true;
  }
  if (s_.window[win_].turn.blend) {
    // Q' = [Omega]x Q, so p = Q^T P has p' = Q^T (P' - Omega x P).
    Vec3 omega;
    const Eigen::Matrix3d q = s_.window[win_].turn.frame.at(t, omega);
    p = q.transpose() * P, dp = q.transpose() * Vec3(dP - omega.cross(P));
    return true;
  }
  // Along the normal: p = Q0^T R_x(theta) P, so p' = Q0^T (R_x(theta) P' + theta' R_x'(theta) P).
  const double th = s_.turn_angle(win_, t), rate = s_.turn_rate(win_, t);
  const double cs = std::cos(th), sn = std::sin(th);
  const Vec3 rP(P.x(), cs * P.y() - sn * P.z(), sn * P.y() + cs * P.z());
  const Vec3 rdP(dP.x(), cs * dP.y() - sn * dP.z(), sn * dP.y() + cs * dP.z());
  const Vec3 turned(0.0, -sn * P.y() - cs * P.z(), cs * P.y() - sn * P.z());
  p = to_tool_ * rP, dp = to_tool_ * Vec3(rdP + rate * turned);
  return true;
}

// A tilted tool: the moving point is the ball point over the node in the tool frame, the lift
// P(q) = (q, -sqrt(R^2 - |q|^2)) of the plan offset q = node - centre, turned. Where the plan
// offset stays within rho_w <= R sin(alpha_w) of the centre, the lift stretches plan lengths by
// at most L = R / h (h = sqrt(R^2 - rho_w^2)), so its speed is at most L |q'|, and its
// acceleration |P''| at most |q''| + (|q'|^2 + rho_w |q''|) / h + rho_w^2 |q'|^2 / h^3 (the
// second derivative of -h). With a correction knot inside, the plan region (the nominal chord
// moved by the correction's box, as for a vertical tool) lifts into the chord between its ends'
// lifts thickened by the lift's bend over it (R^2 len^2 / 8 h^3 for a straight plan segment of
// length len) and L times the region's own thickness. The turn by the frame is a rotation.
PassageGeometry::Span PassageGeometry::lifted_rates(const Sample& sa, const Sample& sb,
                                                    const PlanRegion& r) const {
  const double a = sa.t, b = sb.t, h_t = b - a;
  const double A = table_.accel_xy();
  const bool knot_inside = r.knot_inside;
  const Vec3 &ca = r.ca, &cb = r.cb;
  const double grow = r.grow, v_plan = r.v;
  Span none{0, s_.R, INFINITY, INFINITY, INFINITY, 0};
  if (r.lo >= s_.R) {  // off the ball all along (and so out of contact)
    none.rho_lo = s_.R;
    return none;
  }
  // Next to the ball's rim in plan the lift has no bound (the ball point moves vertically).
  const Lift lift = lift_bounds(s_.R, r.hi, v_plan, A);
  if (lift.hz < 1e-6 * s_.R) return none;
  const double h = lift.hz, L = lift.L;
  Vec3 pa, pb, da, db;
  if (!lifted(a, ca, knot_inside ? Vec3::Zero() : Vec3(sa.v + sa.dv), pa, da) ||
      !lifted(b, cb, knot_inside ? Vec3::Zero() : Vec3(sb.v + sa.dv), pb, db))
    return none;
  // The tool-frame point's chord and the region about it.
  const double ux = pb.x() - pa.x(), uy = pb.y() - pa.y(), len2 = ux * ux + uy * uy;
  const double w = len2 > 0 ? std::clamp(-(pa.x() * ux + pa.y() * uy) / len2, 0.0, 1.0) : 0.0;
  const double chord_lo = norm(pa.x() + w * ux, pa.y() + w * uy);
  const double ends_hi = std::max(norm(pa.x(), pa.y()), norm(pb.x(), pb.y()));
  double thick, v, c_lo, c_hi, accel, length = INFINITY;
  if (!knot_inside) {
    // P'' bound over the piece (q'' = -c'', the centre's plan acceleration at most A).
    accel = lift.accel + turn_accel(L * v_plan);  // and a turning frame's (zero when fixed)
    thick = accel * h_t * h_t / 8 + 1e-12;
    // v = -P' in the tool frame (the vertical code's convention: the centre's velocity).
    v = std::max(norm(da.x(), da.y()), norm(db.x(), db.y())) + accel * h_t / 2;
    const double m_a = -(pa.x() * da.y() - pa.y() * da.x()),
                 m_b = -(pb.x() * db.y() - pb.y() * db.x());
    const double slack = (ends_hi + thick) * accel * h_t / 2;
    c_lo = std::min(m_a, m_b) - slack, c_hi = std::max(m_a, m_b) + slack;
  } else {
    const double len = norm(cb.x() - ca.x(), cb.y() - ca.y());
    // A turning frame moves the whole region by at most |theta'| R h_t about the chord between
    // the ends' points (each taken in its own frame), and the point by |theta'| R more a second.
    thick = s_.R2 * len * len / (8 * h * h * h) + L * grow + turn_speed() * h_t + 1e-12;
    v = L * v_plan + turn_speed();
    c_hi = (ends_hi + thick) * v, c_lo = -c_hi;
    accel = INFINITY;
    // The lift stretches the plan path by at most L, and the frame's turn adds its own.
    length = L * r.length + turn_speed() * h_t;
  }
  const double rho_lo = std::max(0.0, chord_lo - thick), rho_hi = ends_hi + thick;
  return bound_rates(rho_lo, rho_hi, v, c_lo, c_hi, accel, knot_inside, length);
}

bool PassageGeometry::turns_by(double lo, double hi, double turn) const {
  const double w = std::abs(s_.omega), h = (hi - lo) / 4;
  Sample at[5];
  double bound = 0;
  at[0] = sample(lo);
  for (int i = 0; i < 4; ++i) {
    at[i + 1] = sample(i == 3 ? hi : lo + (i + 1) * h);
    const Span part = span(at[i], at[i + 1]);
    if (part.sense(w) <= 0) return false;
    bound += part.top(w) * h;
  }
  if (bound < turn + kTwoPi) return true;
  // The whole turn, exactly: it is the given one to round-off (two crossings agree to 1e-9 rad).
  double sum = 0;
  Probe a = probe(0, lo, at[0].c);
  for (int i = 1; i <= 4; ++i) {
    const Probe b = probe(0, at[i].t, at[i].c);
    sum += advance(at[i - 1].t, a, at[i].t, b);
    a = b;
  }
  return std::abs(std::abs(sum) - turn) < 1e-6;
}

double PassageGeometry::clearance(double out, double speed) const {
  const double k1 = s_.lag_shape.slope_to(out);
  return kRoom * std::sqrt(1 + k1 * k1) * speed / std::abs(s_.omega);
}

bool PassageGeometry::clears_line(double out) const {
  return !tilted_ && !turning_ && line_gap_ >= clearance(out, s_.window[win_].plan_line.speed);
}

// The moment of the centre's velocity about the node, q x v = along(q) across(v) - across(q)
// along(v), keeps the sign of -across(q) and is at least d along_lo - out across_hi in size (d the
// node's least distance from the line); bound_rates' last bound, G' - omega = (|v|^2 / (q x v)) f
// with f within [(1 - S) / 2, (1 + S) / 2] (S from the lag's slope out to `out`), then gives
// G' - omega within (speed_hi^2 / that) [(1 - S) / 2, (1 + S) / 2] in the spindle's sense where
// the node's azimuth turns with the spindle, and within the same times [-(1 + S) / 2, (S - 1) / 2]
// where it turns against it.
std::pair<double, double> PassageGeometry::line_rates(double out) const {
  const PassageSetup::PlanLine& l = s_.window[win_].plan_line;
  const double moment = l.along_lo * line_gap_ - l.across_hi * out;
  if (!(moment > 0) || !(out < s_.profile.reach())) return {INFINITY, INFINITY};
  const double k1 = s_.lag_shape.slope_to(out), S = std::sqrt(1 + k1 * k1);
  const double scale = l.speed_hi * l.speed_hi / moment;
  const double slows = 0.5 * (with_spindle_ ? S - 1 : S + 1) * scale;
  const double speeds = 0.5 * (with_spindle_ ? S + 1 : S - 1) * scale;
  return {slows, speeds};
}

double PassageGeometry::line_gap(double rho, double cap) const {
  const double w = std::abs(s_.omega);
  const auto [fall, rise] = line_rates(rho + s_.window[win_].plan_line.speed_hi * cap);
  return fall < w ? std::min(cap, kTwoPi / (w + rise)) : 0.0;
}

PassageGeometry::Monotony PassageGeometry::monotony_by_span(const Stretch& s) const {
  const double w = std::abs(s_.omega);
  const Span sp = span(std::min(s.a, s.b), std::max(s.a, s.b));
  return {sp.sense(w) > 0, sp.top(w), any_turn_exact()};
}

double PassageGeometry::next_gap(double t, double rho, double dir) const {
  const double half = 0.5 * s_.rev, w = std::abs(s_.omega);
  if (tilted_) {
    // The same in the tool frame, where the ball point moves at most L = R / h times as fast as
    // the plan offset (lifted_rates), h from the farthest the node gets from the centre in plan
    // over the half revolution.
    // The lag's slope first over the whole ball (gap_lag: one number), then only as far out as
    // the point gets.
    // A turning frame adds |theta'| R to the point's speed (turn_speed).
    const Vec3 c = table_(t);
    const double v = s_.window[win_].plan_line.speed,
                 plan_hi = norm(x_ - c.x(), y_ - c.y()) + v * half;
    if (plan_hi < kRimFraction * s_.R) {
      const double L = s_.R / std::sqrt(s_.R2 - plan_hi * plan_hi);
      const double speed = L * v + turn_speed(), moved = speed * half;
      if (rho + moved <= kRimFraction * s_.R) {
        if (rho - kRoom * moved >= kRoom * s_.gap_lag * speed / w) return half;
        if (rho - kRoom * moved >= clearance(rho + moved, speed)) return half;
      }
    }
  } else if (const auto [lo, hi] = s_.window[win_].gap_rho; rho <= hi) {
    if (rho >= lo) return half;
    // Closer in, the same with the lag's slope taken only as far out as the node can get in half
    // a revolution (gap_rho takes it to 0.95 R, where a loxodrome's is twice its tip's), and the
    // axis's least distance also from the pass's line.
    const double v = s_.window[win_].plan_line.speed;
    // The node far enough from the line with the lag's slope over the whole ball (gap_lag, at
    // least the one below): most nodes, settled without the table.
    if (far_from_line()) return half;
    if (std::max(rho - kRoom * v * half, line_gap_) >= clearance(rho + v * half, v)) return half;
  }
  // On a pass that keeps to its line, by the side the node lies on (no table: near the axis most
  // walks end here); the gap may then exceed half a revolution.
  if (const double line = lined() ? line_gap(rho, 1.1 * s_.rev) : 0.0; line > 0) return line;
  const Monotony m = monotony({t, t + dir * half});
  return m.monotone ? std::min(half, kTwoPi / m.top) : 0.0;
}

}  // namespace topomill::plugins
