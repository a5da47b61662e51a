#include "passage_geometry.hpp"

#include <algorithm>
#include <limits>

#include "phase_curvature.hpp"
#include "topomill/interrupt.hpp"

namespace topomill::plugins {

namespace {
// |(x, y)| without hypot's care for overflow, which costs here and is not needed (mm and mm/s).
inline double norm(double x, double y) {
  return std::sqrt(x * x + y * y);
}
// Interpolated centres agree with the path to a nanometre's tenth: far below any grid.
constexpr double kTableTolerance = 1e-7;  // mm
// Windows tabulated between two looks at the stop flag, less one (a mask).
constexpr std::size_t kWindowsPerStopCheck = 1023;
}  // namespace

namespace {
// A bent pass's windows: runs of segments collinear to round-off at one speed (the criterion
// ToolPath uses for a whole pass), so that a line written as many points stays one window. Where
// the data's axis turns, each segment is a window of its own: its frame turns smoothly only
// between its two points (BlendFrame).
std::vector<PassageSetup::Window> windows_of(const ToolPath& path, std::size_t p) {
  const ToolPath::Pass& pass = path.pass(p);
  const bool turns = pass.posture.given && pass.posture.turns;
  const bool line = pass.waypoints.empty() || ((pass.dx != 0 || pass.dy != 0) && !turns);
  if (line) return {{p, 0.0, pass.t_end, 0}};
  std::vector<PassageSetup::Window> out;
  const auto& w = pass.waypoints;
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    const double lo = path.waypoint_time(p, k), hi = path.waypoint_time(p, k + 1);
    if (k > 0) {
      const double before = 0.5 * (path.waypoint_time(p, k - 1) + lo);
      const Vec3 u = path.feed_direction(p, 0.5 * (lo + hi));
      if ((path.feed_direction(p, before) - u).norm() < 1e-12 &&
          std::abs(w[k].speed - w[k - 1].speed) <= 1e-12 * w[k - 1].speed &&
          w[k - 1].axis == w[k].axis && w[k].axis == w[k + 1].axis) {
        out.back().t_hi = hi;
        continue;
      }
    }
    out.push_back({p, lo, hi, k});
  }
  out.front().t_lo = 0.0, out.back().t_hi = pass.t_end;
  return out;
}
}  // namespace

PassageSetup::PassageSetup(const EvaluationRequest& rq, double margin_, int iterations_)
    : path(rq.path),
      tool(rq.tool),
      parallel(false),
      R(rq.tool->radius()),
      R2(R * R),
      omega(rq.path->spindle_rate()),
      speed(INFINITY),
      rev(kTwoPi / std::abs(omega)),
      period(rev / rq.tool->teeth()),
      reach(R + rq.path->max_correction()),
      margin(margin_),
      kappa(rq.kappa),
      iterations(iterations_),
      teeth(rq.tool->teeth()),
      along_y(rq.path->feed_axis() == ToolPath::FeedAxis::Y),
      stop(rq.stop),
      lag_shape(*rq.tool),
      wiggles(rq.path->corrected() || rq.path->runout().offset > 0),
      runout(rq.path->runout().offset) {
  for (int j = 0; j < teeth; ++j) tooth_angle.push_back(tool->tooth_angle(j));
  sin_tip = std::sin(tool->min_polar_angle());
  lag_tip = tool->lag(tool->min_polar_angle());
  for (std::size_t p = 0; p < path->passes(); ++p)
    for (const Window& w : windows_of(*path, p)) window.push_back(w);
  parallel = path->feed_axis() != ToolPath::FeedAxis::None && window.size() == path->passes();
  // A probe may look a revolution beyond either end of a window.
  const double pad = 2 * rev;
  const double k1 = lag_shape.slope_to(0.95 * R);  // the lag's slope over the ball
  gap_lag = std::sqrt(1 + k1 * k1);
  std::shared_ptr<const CorrectionIndex> index;  // the pass's, shared by its windows
  for (const Window& win : window) {
    // Hundreds of thousands of windows take seconds to tabulate: a stop request is looked at.
    if (stop && (centre.size() & kWindowsPerStopCheck) == 0 && stop->load()) throw Interrupted();
    const std::size_t p = win.pass;
    if (!index || win.t_lo == 0)
      index = std::make_shared<const CorrectionIndex>(path->correction_samples(p));
    const double t_lo = win.t_lo, t_hi = win.t_hi, t_mid = 0.5 * (t_lo + t_hi);
    // The feed in plan along the window (the paper's: uniform in Y).
    const Vec3 f = path->feed_direction(p, t_mid);
    speed = std::min(speed, path->pass(p).waypoints.empty()
                                ? path->feed_speed()
                                : path->speed(p, t_mid) * std::hypot(f.x(), f.y()));
    // A window inside a bent pass continues its line beyond its inner ends.
    Stretch stretch;
    stretch.v = f * path->speed(p, t_mid);
    if (t_lo > 0) stretch.lo = t_lo;
    if (t_hi < path->pass(p).t_end) stretch.hi = t_hi;
    centre.emplace_back(*path, p, t_lo - pad, t_hi + pad, kTableTolerance, false, stretch, index);
    if (runout > 0)
      spindle_axis.emplace_back(*path, p, t_lo - pad, t_hi + pad, kTableTolerance, true, stretch,
                                index);
    // A fixed posture keeps the frame over the pass; along the normal over the curvature it
    // turns about X with the inclination (tooth_passage.cpp says which postures are followed).
    const bool tilt = !path->pass(p).posture.vertical();
    tilted.push_back(tilt ? 1 : 0);
    to_tool.push_back(path->tool_frame(p, t_lo).transpose());
    turn.push_back(turn_bounds(*path, win, pad));
    const Vec3 axis = path->axis(p, t_lo);
    tip_offset.emplace_back(tilt ? -R * axis.x() : 0.0, tilt ? -R * axis.y() : 0.0);
    const Vec3 c0 = path->nominal_centre(p, 0.0);
    line.push_back(along_y ? c0.x() : c0.y());
    // The correction is linear between its samples and held beyond: its range is theirs.
    const CorrectionBounds whole = centre.back().correction_bounds(-INFINITY, INFINITY);
    const Vec3 &lo = whole.lo, &hi = whole.hi;
    shift_lo.push_back(lo - Vec3(runout, runout, 0)),
        shift_hi.push_back(hi + Vec3(runout, runout, 0));
    lowest_centre.push_back(centre.back().lowest_z(t_lo, t_hi));
    nominal_speed.push_back(centre.back().top_speed());
    const double v = top_speed(centre.size() - 1, -INFINITY, INFINITY).first, half = 0.5 * rev;
    gap_rho.emplace_back(1.01 * (v * half + gap_lag * v / std::abs(omega)), 0.95 * R - v * half);
    // The line from the window's nominal start to its end in plan; the correction's plan offset
    // at most its box's farthest corner.
    const Vec3 a = path->nominal_centre(p, t_lo), b = path->nominal_centre(p, t_hi);
    const double len = std::hypot(b.x() - a.x(), b.y() - a.y());
    const double sx = std::max(std::abs(lo.x()), std::abs(hi.x()));
    const double sy = std::max(std::abs(lo.y()), std::abs(hi.y()));
    PlanLine l{a.x(), a.y(), 0.0, 0.0, INFINITY, v};
    if (len > 0) {
      l.ux = (b.x() - a.x()) / len, l.uy = (b.y() - a.y()) / len;
      l.off = centre.back().plan_deviation(a, l.ux, l.uy) + std::hypot(sx, sy) + 1e-12;
      if (!wiggles && !tilt && !turn.back().on) {
        const CentreTable::LineSpeeds v = centre.back().line_speeds(l.ux, l.uy);
        if (v.along_lo > 0 && std::isfinite(v.along_hi))  // (not so for a table with no piece)
          l.along_lo = v.along_lo, l.speed_hi = std::hypot(v.along_hi, v.across_hi),
          l.across_hi = v.across_hi;
      }
    }
    plan_line.push_back(l);
    const Vec3 sa = a - path->runout_offset(p, t_lo), sb = b - path->runout_offset(p, t_hi);
    segment.push_back({sa.x(), sa.y(), sb.x(), sb.y(), runout + std::hypot(sx, sy) + 1e-9});
  }
  speed = std::max(speed, 1e-12);
}

double PassageSetup::PlanSegment::distance(double x, double y) const {
  const double ux = bx - ax, uy = by - ay, len2 = ux * ux + uy * uy;
  const double u = len2 > 0 ? std::clamp(((x - ax) * ux + (y - ay) * uy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(x - ax - u * ux, y - ay - u * uy);
}

void PassageSetup::near(double x, double y,
                        std::vector<std::pair<double, std::size_t>>& out) const {
  out.clear();
  for (std::size_t w = 0; w < window.size(); ++w) {
    if (parallel) {
      const double across = std::abs((along_y ? x : y) - line[w]);
      if (across < reach) out.push_back({across, w});
    } else if (const double d = segment[w].distance(x, y) - segment[w].slack; d < R) {
      // Every crossing lies on the ball, no lower than its lowest centre less the sphere's
      // depth at the least distance the centre comes to in plan.
      out.push_back({lowest_centre[w] - std::sqrt(R2 - std::pow(std::max(d, 0.0), 2)), w});
    }
  }
  std::sort(out.begin(), out.end());
}

bool PassageSetup::on_tip_line(std::size_t w, double x, double y) const {
  if (parallel) return std::abs((along_y ? x : y) - tip_line(w)) < PassageGeometry::kOnAxis;
  if (turn[w].on) {
    // The tip's path bends as the frame turns: where the tip is level with the node, whether it
    // is over it (to a micrometre: tip_height then asks for kOnAxis).
    const double t = tip_time(w, x, y);
    if (!std::isfinite(t)) return false;
    const Vec3 tip = centre[w](t) - R * Vec3(to_tool_at(w, t).row(2).transpose());
    return std::hypot(tip.x() - x, tip.y() - y) < 1e-3;
  }
  const PlanLine& l = plan_line[w];
  const double dx = x - l.x - tip_offset[w].first, dy = y - l.y - tip_offset[w].second;
  return std::abs(l.ux * dy - l.uy * dx) < PassageGeometry::kOnAxis &&
         std::isfinite(l.off);  // a window that moves in plan
}

std::pair<double, double> PassageSetup::top_speed(std::size_t p, double ta, double tb) const {
  const auto [h, v] = nominal_speed[p];
  const CorrectionBounds c = centre[p].correction_bounds(ta, tb);
  return {h + c.speed_xy, v + c.speed_z};
}

PassageSetup::Turn PassageSetup::turn_bounds(const ToolPath& path, const Window& w, double pad) {
  Turn q;
  const std::size_t p = w.pass;
  const ToolPath::Pass& pass = path.pass(p);
  if (!pass.posture.turns) return q;
  // theta (or the blend's angular velocity) on 1024 steps over the window and the look beyond
  // it: first and second differences (or the velocity and its differences), with a margin (both
  // are smooth: the inclination of a smooth surface under a uniform feed; the blend's frame,
  // continued at a constant rate).
  constexpr int kSteps = 1024;
  const double t0 = w.t_lo - pad, dt = (w.t_hi - w.t_lo + 2 * pad) / kSteps;
  if (pass.posture.given) {
    const Vec3 &a0 = pass.waypoints[w.segment].axis, &a1 = pass.waypoints[w.segment + 1].axis;
    if (a0 == a1) return q;  // the pass turns elsewhere: this window's frame is fixed
    q.on = q.blend = true;
    q.frame = BlendFrame(a0, a1, w.t_lo, w.t_hi);
    Vec3 prev;
    for (int k = 0; k <= kSteps; ++k) {
      Vec3 omega;
      q.frame.at(t0 + k * dt, omega);
      q.rate = std::max(q.rate, omega.norm());
      if (k >= 1) q.accel = std::max(q.accel, (omega - prev).norm() / dt);
      prev = omega;
    }
  } else {
    if (!pass.posture.normal) return q;
    q.on = true;
    q.lambda0 = path.surface().inclination(path.surface_y(p, 0.0));
    double prev = NAN, prev2 = NAN;
    for (int k = 0; k <= kSteps; ++k) {
      const double th = path.surface().inclination(path.surface_y(p, t0 + k * dt));
      if (k >= 1) q.rate = std::max(q.rate, std::abs(th - prev) / dt);
      if (k >= 2) q.accel = std::max(q.accel, std::abs(th - 2 * prev + prev2) / (dt * dt));
      prev2 = prev, prev = th;
    }
  }
  q.rate = 1.25 * q.rate + 1e-12, q.accel = 1.25 * q.accel + 1e-9;
  return q;
}

double PassageSetup::turn_angle(std::size_t w, double t) const {
  return path->surface().inclination(path->surface_y(window[w].pass, t)) - turn[w].lambda0;
}

double PassageSetup::turn_rate(std::size_t w, double t) const {
  const SurfaceShape& surface = path->surface();
  const std::size_t p = window[w].pass;
  const double y = path->surface_y(p, t), h = 1e-5;  // mm: theta' to about 1e-12 of itself
  return (surface.inclination(y + h) - surface.inclination(y - h)) / (2 * h) *
         (path->feed_speed() * path->pass(p).dy);
}

Eigen::Matrix3d PassageSetup::to_tool_at(std::size_t p, double t) const {
  if (!turn[p].on) return to_tool[p];
  if (turn[p].blend) return turn[p].frame.at(t).transpose();
  const double th = turn_angle(p, t), c = std::cos(th), s = std::sin(th);
  Eigen::Matrix3d r;  // R_x(theta): Q(t)^T = Q(0)^T R_x(theta)
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return to_tool[p] * r;
}

double PassageSetup::level_time(std::size_t w, double x, double y) const {
  const double t_lo = window[w].t_lo, t_hi = window[w].t_hi;
  const ToolPath::Pass& pass = path->pass(window[w].pass);
  // Signed along the window's feed (a reversed pass feeds towards -Y or -X), so that it grows.
  const PlanLine& l = plan_line[w];
  const double sign = along_y ? pass.dy : pass.dx;
  auto along = [&](double t) {
    const Vec3 c = centre[w].nominal(t);
    if (!parallel) return l.ux * (c.x() - x) + l.uy * (c.y() - y);
    return sign * (along_y ? c.y() - y : c.x() - x);
  };
  double t0 = t_lo, f0 = along(t_lo), t1 = t_hi, f1 = along(t_hi);
  if (f0 > reach || f1 < -reach) return NAN;  // the window never comes level with the node
  for (int k = 0; k < 8 && f1 != f0; ++k) {
    const double t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
    t0 = t1, f0 = f1, t1 = std::clamp(t2, t_lo, t_hi), f1 = along(t1);
    if (std::abs(f1) < 1e-12) break;
  }
  return t1;
}

std::pair<double, double> PassageSetup::contact_radii(std::size_t w, double t) const {
  // The contact's polar angle about the axis: |lambda| for a vertical tool.
  const double lambda = path->contact_angle(window[w].pass, t);
  const double lo = std::max(0.0, lambda - margin * kappa);
  const double hi = std::min(M_PI / 2, lambda + margin * kappa);
  return {R * std::sin(lo), R * std::sin(hi)};
}

double PassageGeometry::crossing(int tooth, double t, double& slope, Probe& last) const {
  double g_prev = 0, t_prev = t;
  last = {false, INFINITY, INFINITY, INFINITY, NAN};
  for (int k = 0; k < s_.iterations; ++k) {
    const Sample at = sample(t);
    last = probe(tooth, t, at.c);
    const double gk = last.g;
    if (converged(last)) break;
    // Newton's step on the phase's own rate; the secant where that is too flat to step by (or
    // undefined: on the axis). Near the axis, where the rate swings by v / rho within a passage,
    // this takes a quarter fewer probes than the secant alone did.
    double lag_rate = 0;
    if (const double r = rate(at, at.dv, &lag_rate); std::abs(r) > 0.1 * std::abs(s_.omega)) {
      slope = r;
      if (land(at, r, lag_rate, t, last)) break;
    } else if (k > 0 && t != t_prev && std::abs(gk - g_prev) < M_PI) {
      const double sec = (gk - g_prev) / (t - t_prev);
      if (std::abs(sec) > 0.1 * std::abs(s_.omega)) slope = sec;
    }
    g_prev = gk, t_prev = t;
    t -= gk / slope;
  }
  return t;
}

PassageGeometry::Span PassageGeometry::span(const Sample& sa, const Sample& sb,
                                            const Vec3* na_known, const Vec3* nb_known) const {
  if (tilted_) return span_tilted(sa, sb, na_known, nb_known);
  const double a = sa.t, b = sb.t;
  const double step = s_.path->correction_step(src_);
  const double A = table_.accel_xy(), h = b - a;
  // rho's range, the centre's top speed in plan, and the range [c_lo, c_hi] of the moment of its
  // velocity about the node, q x v (q the node's offset from the axis).
  double rho_lo, rho_hi, v, c_lo, c_hi, length = INFINITY, box_z_lo = NAN;
  const double first_knot = step > 0 ? std::max(0.0, std::floor(a / step) + 1) * step : INFINITY;
  const bool knot_inside = step > 0 && first_knot < b && first_knot <= last_knot();
  if (!knot_inside) {
    // One smooth piece: the (tabulated) centre lies within A h^2 / 8 of its chord (plus round-off
    // ), its speed within A h / 2 of the larger at the ends, and q x v (whose rate is q x v', as
    // q' = -v) within rho A h / 2 of the range at the ends.
    // The correction's slope is one over the piece: the one starting at a (at b a knot may
    // start the next).
    const Vec3 &ca = sa.c, &cb = sb.c, va = sa.v + sa.dv, vb = sb.v + sa.dv;
    const double sag = A * h * h / 8 + 1e-12;
    const double u = nearest_on_chord(ca, cb);
    const double ax = x_ - ca.x(), ay = y_ - ca.y(), bx = x_ - cb.x(), by = y_ - cb.y();
    rho_lo = std::max(0.0, norm(ax - u * (cb.x() - ca.x()), ay - u * (cb.y() - ca.y())) - sag);
    rho_hi = std::max(norm(ax, ay), norm(bx, by)) + sag;
    v = std::max(norm(va.x(), va.y()), norm(vb.x(), vb.y())) + A * h / 2;
    const double m_a = ax * va.y() - ay * va.x(), m_b = bx * vb.y() - by * vb.x();
    const double slack = rho_hi * A * h / 2;
    c_lo = std::min(m_a, m_b) - slack, c_hi = std::max(m_a, m_b) + slack;
  } else {
    // Several pieces of the correction: the centre is the nominal one (within its sagitta of
    // the chord) moved by a correction within the box it keeps to over [a, b]; so within the
    // chord moved to the box's middle, thickened by the sagitta and the box's half diagonal (a
    // convex region, as advance() needs).
    const CorrectionBounds box = table_.correction_bounds(a, b);
    const Vec3 &lo = box.lo, &hi = box.hi, mid = 0.5 * (lo + hi);
    const Vec3 na = na_known ? *na_known : table_.nominal(a);
    const Vec3 nb = nb_known ? *nb_known : table_.nominal(b), ca = na + mid, cb = nb + mid;
    box_z_lo = lo.z();
    const double grow = A * h * h / 8 + 0.5 * norm(hi.x() - lo.x(), hi.y() - lo.y()) + 1e-12;
    const double u = nearest_on_chord(ca, cb);
    const double ax = x_ - ca.x(), ay = y_ - ca.y(), bx = x_ - cb.x(), by = y_ - cb.y();
    rho_lo = std::max(0.0, norm(ax - u * (cb.x() - ca.x()), ay - u * (cb.y() - ca.y())) - grow);
    rho_hi = std::max(norm(ax, ay), norm(bx, by)) + grow;
    v = s_.nominal_speed[win_].first + box.speed_xy;
    c_hi = rho_hi * v, c_lo = -c_hi;
    // The centre's path: the nominal one's at most its top speed a second, the correction's
    // its own pieces' lengths.
    length = s_.nominal_speed[win_].first * h + table_.correction_length(a, b);
  }
  Span out = bound_rates(rho_lo, rho_hi, v, c_lo, c_hi, A, knot_inside, length);
  out.plan_lo = rho_lo, out.box_z_lo = box_z_lo;
  return out;
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
  // (was S v / d = 1.15 v / d), and 0 for an edge with no lag at the tip.
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
  if (s_.turn[win_].blend) {
    // Q' = [Omega]x Q, so p = Q^T P has p' = Q^T (P' - Omega x P).
    Vec3 omega;
    const Eigen::Matrix3d q = s_.turn[win_].frame.at(t, omega);
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
PassageGeometry::Span PassageGeometry::span_tilted(const Sample& sa, const Sample& sb,
                                                   const Vec3* na_known,
                                                   const Vec3* nb_known) const {
  const double a = sa.t, b = sb.t, h_t = b - a;
  const double step = s_.path->correction_step(src_);
  const double A = table_.accel_xy();
  const double first_knot = step > 0 ? std::max(0.0, std::floor(a / step) + 1) * step : INFINITY;
  const bool knot_inside = step > 0 && first_knot < b && first_knot <= last_knot();
  // The plan region first: its chord, thickness, the plan offset's range and top speed.
  Vec3 ca, cb;
  double grow, v_plan, box_z_lo = NAN;
  if (!knot_inside) {
    ca = sa.c, cb = sb.c, grow = A * h_t * h_t / 8 + 1e-12;
    const Vec3 va = sa.v + sa.dv, vb = sb.v + sa.dv;
    v_plan = std::max(norm(va.x(), va.y()), norm(vb.x(), vb.y())) + A * h_t / 2;
  } else {
    const CorrectionBounds box = table_.correction_bounds(a, b);
    const Vec3 &lo = box.lo, &hi = box.hi, mid = 0.5 * (lo + hi);
    const Vec3 na = na_known ? *na_known : table_.nominal(a);
    const Vec3 nb = nb_known ? *nb_known : table_.nominal(b);
    ca = na + mid, cb = nb + mid;
    box_z_lo = lo.z();
    grow = A * h_t * h_t / 8 + 0.5 * norm(hi.x() - lo.x(), hi.y() - lo.y()) + 1e-12;
    v_plan = s_.nominal_speed[win_].first + box.speed_xy;
  }
  const double u = nearest_on_chord(ca, cb);
  const double ax = x_ - ca.x(), ay = y_ - ca.y(), bx = x_ - cb.x(), by = y_ - cb.y();
  const double plan_lo =
      std::max(0.0, norm(ax - u * (cb.x() - ca.x()), ay - u * (cb.y() - ca.y())) - grow);
  const double plan_hi = std::max(norm(ax, ay), norm(bx, by)) + grow;
  Span none{0, s_.R, INFINITY, INFINITY, INFINITY, 0};
  none.plan_lo = plan_lo;
  if (plan_lo >= s_.R) {  // off the ball all along (and so out of contact)
    none.rho_lo = s_.R;
    return none;
  }
  // Next to the ball's rim in plan the lift has no bound (the ball point moves vertically).
  const Lift lift = lift_bounds(s_.R, plan_hi, v_plan, A);
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
    length = L * (s_.nominal_speed[win_].first * h_t + table_.correction_length(a, b)) +
             turn_speed() * h_t;
  }
  const double rho_lo = std::max(0.0, chord_lo - thick), rho_hi = ends_hi + thick;
  Span out = bound_rates(rho_lo, rho_hi, v, c_lo, c_hi, accel, knot_inside, length);
  out.plan_lo = plan_lo, out.box_z_lo = box_z_lo;
  return out;
}

bool PassageGeometry::turns_by(double lo, double hi, double turn) const {
  const double w = std::abs(s_.omega), h = (hi - lo) / 4;
  Sample at[5];
  double bound = 0;
  at[0] = sample(lo);
  for (int i = 0; i < 4; ++i) {
    at[i + 1] = sample(i == 3 ? hi : lo + (i + 1) * h);
    const Span part = span(at[i], at[i + 1]);
    if (!part.monotone(w)) return false;
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
  return 1.01 * std::sqrt(1 + k1 * k1) * speed / std::abs(s_.omega);
}

bool PassageGeometry::clears_line(double out) const {
  return !tilted_ && !turning_ && line_gap_ >= clearance(out, s_.plan_line[win_].speed);
}

std::pair<double, double> PassageGeometry::line_rates(double out) const {
  const PassageSetup::PlanLine& l = s_.plan_line[win_];
  const double moment = l.along_lo * line_gap_ - l.across_hi * out;
  if (!(moment > 0) || !(out < s_.R)) return {INFINITY, INFINITY};
  const double k1 = s_.lag_shape.slope_to(out), S = std::sqrt(1 + k1 * k1);
  const double scale = l.speed_hi * l.speed_hi / moment;
  const double slows = 0.5 * (with_spindle_ ? S - 1 : S + 1) * scale;
  const double speeds = 0.5 * (with_spindle_ ? S + 1 : S - 1) * scale;
  return {slows, speeds};
}

double PassageGeometry::line_gap(double rho, double cap) const {
  const double w = std::abs(s_.omega);
  const auto [fall, rise] = line_rates(rho + s_.plan_line[win_].speed_hi * cap);
  return fall < w ? std::min(cap, kTwoPi / (w + rise)) : 0.0;
}

bool PassageGeometry::monotone_around(double t, double duration) const {
  if (tilted_ || turning_) return false;  // (before reading the table: it never holds then)
  const Vec3 c = table_(t);
  return monotone_from(norm(x_ - c.x(), y_ - c.y()), duration);
}

double PassageGeometry::next_gap(double t, double rho, double dir) const {
  const double half = 0.5 * s_.rev, w = std::abs(s_.omega);
  if (tilted_) {
    // The same in the tool frame, where the ball point moves at most L = R / h times as fast as
    // the plan offset (span_tilted), h from the farthest the node gets from the centre in plan
    // over the half revolution.
    // The lag's slope first over the whole ball (gap_lag: one number), then only as far out as
    // the point gets.
    // A turning frame adds |theta'| R to the point's speed (turn_speed).
    const Vec3 c = table_(t);
    const double v = s_.plan_line[win_].speed, plan_hi = norm(x_ - c.x(), y_ - c.y()) + v * half;
    if (plan_hi < 0.95 * s_.R) {
      const double L = s_.R / std::sqrt(s_.R2 - plan_hi * plan_hi);
      const double speed = L * v + turn_speed(), moved = speed * half;
      if (rho + moved <= 0.95 * s_.R) {
        if (rho - 1.01 * moved >= 1.01 * s_.gap_lag * speed / w) return half;
        if (rho - 1.01 * moved >= clearance(rho + moved, speed)) return half;
      }
    }
  } else if (const auto [lo, hi] = s_.gap_rho[win_]; rho <= hi) {
    if (rho >= lo) return half;
    // Closer in, the same with the lag's slope taken only as far out as the node can get in half
    // a revolution (gap_rho takes it to 0.95 R, where a loxodrome's is twice its tip's), and the
    // axis's least distance also from the pass's line.
    const double v = s_.plan_line[win_].speed;
    // The node far enough from the line with the lag's slope over the whole ball (gap_lag, at
    // least the one below): most nodes, settled without the table.
    if (far_from_line()) return half;
    if (std::max(rho - 1.01 * v * half, line_gap_) >= clearance(rho + v * half, v)) return half;
  }
  // On a pass that keeps to its line, by the side the node lies on (no table: near the axis most
  // walks end here); the gap may then exceed half a revolution.
  if (const double line = lined() ? line_gap(rho, 1.1 * s_.rev) : 0.0; line > 0) return line;
  const Span sp = span(std::min(t, t + dir * half), std::max(t, t + dir * half));
  return sp.monotone(w) ? std::min(half, kTwoPi / sp.top(w)) : 0.0;
}

bool PassageGeometry::land(const Sample& at, double r, double lag_rate, double& t, Probe& q) const {
  if (turning_) return false;
  const double dt = -q.g / r, t1 = at.t + dt, h = std::abs(dt);
  // The correction is linear between knots: with one inside, G' may jump (no bound of G'').
  const double step = s_.path->correction_step(src_);
  if (step > 0 && std::floor(at.t / step) != std::floor(t1 / step) &&
      std::min(at.t, t1) <= last_knot())
    return false;
  // The moving point (the node's offset from the axis; tilted, the ball point over it in the
  // tool frame) moves at most at `speed` with at most `accel` over the step, so its rho stays
  // within [rho_lo, rho_hi].
  const double A = table_.accel_xy(), centre_accel = table_.accel();
  const Vec3 v = at.v + at.dv;
  const double v_plan = std::sqrt(v.x() * v.x() + v.y() * v.y()) + A * h;
  double speed = v_plan, accel = A;
  if (tilted_) {
    const Lift lift = lift_bounds(s_.R, norm(x_ - at.c.x(), y_ - at.c.y()) + v_plan * h, v_plan, A);
    if (lift.hz < 1e-6 * s_.R) return false;
    speed = lift.L * v_plan, accel = lift.accel;
  }
  const double rho_lo = q.rho - speed * h, rho_hi = q.rho + speed * h;
  if (!(rho_lo > 0)) return false;
  const LagShape::Bound k = s_.lag_shape.over(rho_lo, rho_hi);
  if (k.kink || !std::isfinite(k.k1) ||
      0.5 * phase_curvature(k.k1, k.k2, speed, accel, rho_lo) * h * h > 1e-10 ||
      0.5 * centre_accel * h * h > 1e-13)
    return false;
  const Vec3 c = at.c + v * dt;
  const double dx = x_ - c.x(), dy = y_ - c.y(), r2 = dx * dx + dy * dy;
  if (!(r2 < s_.R2)) return false;
  const double below = std::sqrt(s_.R2 - r2);
  double rho = std::sqrt(r2);
  bool over = rho >= rho_lo_ && rho <= rho_hi_;
  if (tilted_) {
    const Vec3 p = to_tool_ * Vec3(dx, dy, -below);
    rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
    over = p.z() <= 0 && rho >= rho_lo_ && rho <= rho_hi_;
  }
  t = t1;
  q = {over, 0.0, c.z() - below, rho, q.lag + lag_rate * dt};
  return true;
}

double PassageGeometry::rate(const Sample& at, const Vec3& dv, double* lag_rate) const {
  if (tilted_) {
    // The same in the tool frame: q the ball point's offset from the axis, q' its velocity.
    Vec3 p, dp;
    if (!lifted(at.t, at.c, at.v + dv, p, dp)) return NAN;
    const double r2 = p.x() * p.x() + p.y() * p.y();
    if (!(r2 > 0)) return NAN;
    const double du = (p.x() * dp.x() + p.y() * dp.y()) / r2,
                 daz = (p.x() * dp.y() - p.y() * dp.x()) / r2;
    const double sin_a = std::sqrt(r2) / s_.R;
    if (sin_a >= 1) return NAN;
    const double lag = s_.lag_shape.slope(sin_a, std::abs(p.z()) / s_.R, *s_.tool) * du;
    if (lag_rate) *lag_rate = lag;
    return s_.omega + lag - daz;
  }
  const Vec3 &c = at.c, v = at.v + dv;
  const double qx = x_ - c.x(), qy = y_ - c.y(), r2 = qx * qx + qy * qy;
  if (!(r2 > 0)) return NAN;
  // q' = -v: u' = (q . q') / r2, az' = (q x q') / r2.
  const double du = -(qx * v.x() + qy * v.y()) / r2, daz = -(qx * v.y() - qy * v.x()) / r2;
  const double sin_a = std::sqrt(r2) / s_.R;
  if (sin_a >= 1) return NAN;
  const double lag = s_.lag_shape.slope(sin_a, std::sqrt(1 - sin_a * sin_a), *s_.tool) * du;
  if (lag_rate) *lag_rate = lag;
  return s_.omega + lag - daz;
}

double PassageGeometry::split_time(double lo, double hi) const {
  const double step = s_.path->correction_step(src_), mid = 0.5 * (lo + hi);
  if (!(step > 0)) return mid;
  const double top = last_knot() / step;  // the last knot's index
  // The middle half's knots, ka .. kb: of those, the one with the most trailing zeros is kb with
  // its bits below the highest bit where ka and kb differ cleared.
  const double ka = std::max(std::ceil((lo + 0.25 * (hi - lo)) / step), 0.0);
  const double kb = std::min(std::floor((hi - 0.25 * (hi - lo)) / step), top);
  if (ka <= kb && kb < 0x1p52) {
    const auto a = static_cast<std::uint64_t>(ka), b = static_cast<std::uint64_t>(kb);
    const std::uint64_t k =
        a == b ? b : b & ~((std::uint64_t{1} << (63 - __builtin_clzll(a ^ b))) - 1);
    if (const double t = static_cast<double>(k) * step; t > lo && t < hi) return t;
  }
  // A piece shorter than two steps: the knot nearest the middle, if any.
  for (const double k : {std::round(mid / step), std::floor(mid / step), std::ceil(mid / step)})
    if (const double t = k * step; t > lo && t < hi && k >= 0 && k <= top) return t;
  return mid;
}

// Cut [a, b] in halves until each piece is settled. On a piece of length h with ends' phases
// g_a, g_b (each tooth's, wrapped to its nearest crossing):
// - no tooth can cross there: |g_a| + |g_b| > top h for each (top the bound of |G'|), the phase
//   cannot reach zero and back;
// - no crossing under the ball can lie below `below` there (the ball too high, or out of contact);
// - G monotone (fall < |omega|, rise < -|omega|, or G' of one sign at both ends with room for
//   the curvature): G is known unwrapped across the piece (advance: the bounds need rho_lo > 0,
//   so the axis cannot come round the node), and every tooth's crossings are the levels it
//   passes, each solved in its bracket (solve_level). Far from the axis a whole revolution
//   settles at once;
// - the axis within kOnAxis of the node all along: the tip cuts it there.
// Pieces are split at a correction knot inside first (G' jumps there: split_time), else at the
// middle; below a 1e-10 revolution the sign change alone decides (a touch of the edge no grid can
// resolve).
void PassageGeometry::crossings_in(int only, double a, double b, double& below,
                                   std::vector<Crossing>& roots, Probe* ends) const {
  struct End {
    Sample at;
    Probe q;      // tooth 0's
    double rate;  // NaN until needed
    Vec3 n;       // the nominal centre (span's, where knots lie inside: not read from the table)
  };
  struct Piece {
    End lo, hi;
  };
  const double w = std::abs(s_.omega), min_len = 1e-10 * s_.rev;
  // A piece whose ball stays within round-off of `below` (which falls as crossings are found)
  // holds nothing lower that counts. Next to the tip (a point of every edge, and the ball's
  // lowest near the axis) the pieces' floor equals the tip's height but for round-off: without
  // the tie they were halved down to kOnAxis before anything ruled them out.
  auto above = [&](double floor) {
    return floor >= below - 16 * std::numeric_limits<double>::epsilon() * (std::abs(below) + s_.R);
  };
  const int first = only < 0 ? 0 : only, last = only < 0 ? s_.teeth - 1 : only;
  // The probes' phases carry round-off of a few ulps of their largest terms (omega t, the pass's
  // phase, the wrap). Where the phase turns at exactly its bound's rate (a node on the pass's line
  // with no lag turning there: the azimuth stands still, so G' = omega and the bound is tight), a
  // crossing inside a piece makes |g_a| + |g_b| equal its reach but for that round-off, which must
  // not rule the crossing out: without the allowance it does in 158 of the 360 windows of
  // tests/plugins/exact_window_test.cpp, and on the convex case's pass line a crossing 0.11 nm
  // below the tip's cut is lost so.
  const double roundoff = 32 * std::numeric_limits<double>::epsilon() *
                          (w * std::max(std::abs(a), std::abs(b)) + std::abs(phase_) + 8 * M_PI);
  // Tooth j's phase is tooth 0's turned by its angle: one probe serves all.
  auto offset = [&](int j) { return s_.tooth_angle[j] - s_.tooth_angle[0]; };
  // The first whole turn m at or above phase v for tooth j: its level is m 2 pi - offset(j).
  auto first_turn = [&](double v, int j) { return std::ceil((v + offset(j)) / kTwoPi); };
  auto end = [&](double t) {
    Vec3 n;
    const Sample at = sample(t, n);
    return End{at, probe(0, t, at.c), NAN, n};
  };
  // The rate at an end on the side of a piece whose correction slope is dv (kept: an end is
  // shared by two pieces, on the same slope except at a knot).
  auto rate_of = [&](End& e, const Vec3& dv) {
    if (e.at.dv != dv) return rate(e.at, dv);
    if (std::isnan(e.rate)) e.rate = rate(e.at, dv);
    return e.rate;
  };
  // The ball's lowest possible height over the node on a piece.
  auto floor_of = [&](const Piece& p, const Span& sp) {
    if (sp.plan_lo >= s_.R) return double(INFINITY);
    const double a = p.lo.at.t, b = p.hi.at.t;
    // The nominal centre's lowest, and the correction's (its box's, where span read it).
    const double shift = !std::isnan(sp.box_z_lo) ? sp.box_z_lo
                         : table_.corrected()     ? table_.correction_bounds(a, b).lo.z()
                                                  : 0.0;
    const double z = table_.nominal_lowest_z(a, b, p.lo.n.z(), p.hi.n.z()) + shift;
    return z - std::sqrt(s_.R2 - sp.plan_lo * sp.plan_lo);
  };
  auto found = [&](int tooth, double t) {
    const Probe q = probe(tooth, t);
    roots.push_back({tooth, t, q});
    if (q.over) below = std::min(below, q.height);
  };
  // The pieces still to settle, in storage kept by the caller's thread from call to call (an
  // allocation each call was 4 % of the halving's instructions at lambda 0 with effects), taken
  // into a local for the call: every use of a thread_local in a shared library is a call to find
  // it (2 % of the instructions there).
  thread_local std::vector<Piece> kept;
  std::vector<Piece> stack;
  stack.swap(kept);
  stack.clear();
  // Whether piece p is settled (its crossings, if any, found); false when it must be halved.
  auto settle = [&](Piece& p) {
    const double h = p.hi.at.t - p.lo.at.t;
    const Span sp = span(p.lo.at, p.hi.at, &p.lo.n, &p.hi.n);
    if (sp.rho_hi <= kOnAxis) {
      // The axis within kOnAxis of the node all along: the tip, a point of every edge, cuts it
      // here (g jumps by pi rather than crossing zero, and no subdivision settles it).
      found(first, 0.5 * (p.lo.at.t + p.hi.at.t));
      return true;
    }
    const double reach = sp.turn(w, h) + roundoff;
    bool reachable = false;
    for (int j = first; j <= last && !reachable; ++j)
      reachable =
          std::abs(wrap(p.lo.q.g + offset(j))) + std::abs(wrap(p.hi.q.g + offset(j))) <= reach;
    if (!reachable) return true;
    if (sp.rho_lo > rho_hi_ || sp.rho_hi < rho_lo_ || above(floor_of(p, sp))) return true;
    // Monotone: turn < |omega|, or G' of one sign at both ends with room for the curvature (G'
    // is then at least half their sum less the curvature's fall between).
    bool mono = sp.monotone(w) || sp.falls(w);
    if (!mono && std::isfinite(sp.curve)) {
      const double ra = rate_of(p.lo, p.lo.at.dv), rb = rate_of(p.hi, p.lo.at.dv);
      mono = (ra > 0) == (rb > 0) && 0.5 * (std::abs(ra) + std::abs(rb) - sp.curve * h) > 0;
      if (!mono) {
        // A turn-back inside: G stays within what its ends' phases and rates allow under the
        // curvature bound (phase_range); where no tooth's level lies in that range, no crossing
        // does.
        const double g_lo = p.lo.q.g, g_hi = g_lo + advance(p.lo.at.t, p.lo.q, p.hi.at.t, p.hi.q);
        const auto [v_lo, v_hi] = phase_range(g_lo, g_hi, ra, rb, sp.curve, h);
        bool level = false;
        for (int j = first; j <= last && !level; ++j)
          level = first_turn(v_lo - 1e-9, j) * kTwoPi - offset(j) <= v_hi + 1e-9;
        if (!level) return true;
      }
    }
    if (mono) {
      // Unwrapped from the piece's start (rho_lo > 0: the turn is exact), every tooth's levels
      // G = 2 pi m - offset(j) between its ends.
      const double g_lo = p.lo.q.g, g_hi = g_lo + advance(p.lo.at.t, p.lo.q, p.hi.at.t, p.hi.q);
      const double v_lo = std::min(g_lo, g_hi), v_hi = std::max(g_lo, g_hi);
      for (int j = first; j <= last; ++j)
        for (double m = first_turn(v_lo, j); m * kTwoPi - offset(j) <= v_hi; ++m)
          found(j, solve_level(p.lo.at.t, p.lo.q, p.hi.at.t, g_hi, m * kTwoPi - offset(j)));
      return true;
    }
    if (h < min_len) {
      for (int j = first; j <= last; ++j) {
        const double ga = wrap(p.lo.q.g + offset(j)), gb = wrap(p.hi.q.g + offset(j));
        if (crosses(ga, gb)) found(j, solve_bracket(j, p.lo.at.t, p.hi.at.t, ga, gb));
      }
      return true;
    }
    return false;
  };
  // Depth first, the piece in hand kept out of the stack (a push and a pop of two ends saved
  // at each halving, and the rate at the end it keeps).
  Piece p{end(a), end(b)};
  if (ends) ends[0] = p.lo.q, ends[1] = p.hi.q;
  // A stop request is honoured here too: on a steep face one node's pieces can take a minute.
  while (!s_.stopped()) {
    if (!settle(p)) {
      const End mid = end(split_time(p.lo.at.t, p.hi.at.t));
      // The half nearer the axis first: it holds the lowest crossings, which prune the other.
      if (p.lo.q.rho < p.hi.q.rho)
        stack.push_back(Piece{mid, p.hi}), p.hi = mid;
      else
        stack.push_back(Piece{p.lo, mid}), p.lo = mid;
      continue;
    }
    if (stack.empty()) break;
    p = stack.back();
    stack.pop_back();
  }
  kept.swap(stack);
}

namespace {
// The zero of f in [lo, hi], where f(lo) = f_lo and f(hi) = f_hi differ in sign and f is
// monotone: regula falsi with the Illinois rule (the end kept twice has its value halved), to
// |f| < 1e-9 or a bracket narrower than `width`.
template <class F>
double illinois(F f, double lo, double hi, double f_lo, double f_hi, double width) {
  if (f_lo == 0) return lo;
  if (f_hi == 0) return hi;
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > width; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double ft = f(t);
    if (std::abs(ft) < 1e-9) return t;
    if ((ft < 0) == (f_lo < 0)) {
      lo = t, f_lo = ft;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = t, f_hi = ft;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}
}  // namespace

double PassageGeometry::solve_level(double ta, const Probe& a, double b, double g_b,
                                    double level) const {
  // f = G - level, G unwrapped from ta (advance).
  return illinois([&](double t) { return a.g + advance(ta, a, t, probe(0, t)) - level; }, ta, b,
                  a.g - level, g_b - level, 1e-13 * s_.rev);
}

double PassageGeometry::solve_bracket(int tooth, double lo, double hi, double g_lo,
                                      double g_hi) const {
  return illinois([&](double t) { return probe(tooth, t).g; }, lo, hi, g_lo, g_hi, 1e-13 * s_.rev);
}

double PassageGeometry::bisect(int tooth, double lo, double hi, double g_lo) const {
  for (int it = 0; it < 200 && hi - lo > 1e-13 * s_.rev; ++it) {
    const double mid = 0.5 * (lo + hi), g_mid = probe(tooth, mid).g;
    if ((g_mid < 0) == (g_lo < 0))
      lo = mid, g_lo = g_mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double PassageGeometry::walk(double t_b, std::vector<Crossing>& roots, std::uint64_t& visited,
                             double below, Crossing* lowest) const {
  const double t_lo = this->t_lo(), t_hi = this->t_hi(), rev = s_.rev;
  double best = INFINITY;
  for (int dir : {+1, -1}) {
    for (int m = (dir > 0 ? 0 : 1); m < 100000; ++m) {
      // Revolution m from t_b: [t_b + (m - 1/2) rev, t_b + (m + 1/2) rev], and beyond its near
      // edge all later ones: past the bound's bottom (t_b is within a 20th of a tooth period of
      // it), if the bound is too high there, nothing from here on can lower the node.
      const double lo = t_b + (dir * m - 0.5) * rev, hi = lo + rev;
      if (hi < t_lo || lo > t_hi) break;
      const double edge = dir > 0 ? lo : hi;
      if (m > 0 && dir * (edge - t_b) >= 0.05 * s_.period && bound(edge) >= std::min(best, below))
        break;
      double limit = std::min(best, below);
      roots.clear();
      crossings_in(-1, std::max(lo, t_lo), std::min(hi, t_hi), limit, roots);  // every tooth
      for (const Crossing& r : roots) {
        const Probe& q = r.q;
        ++visited;
        if (q.over && std::isfinite(q.height) && q.height < best) {
          best = q.height;
          if (lowest) *lowest = r;
        }
      }
    }
  }
  return best;
}

}  // namespace topomill::plugins
