// PassageGeometry's phase at one node: the probe's rate, Newton's crossing and its proven landing.
#include "passage_geometry.hpp"

#include <algorithm>

#include "phase_curvature.hpp"

namespace topomill::plugins {

// The point on the equator's plane, and the lag held at the rim's (sin 1, cos 0) as LagShape
// continues it: continuous with the ball's probe at the rim, no edge, no height.
Probe PassageGeometry::probe_past_rim(int tooth, double t, double dx, double dy) const {
  const Vec3 p = tilted_ ? Vec3(to_tool(t) * Vec3(dx, dy, 0.0)) : Vec3(dx, dy, 0.0);
  const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
  const double sin_a = std::min(rho / s_.R, 1.0), cos_a = std::sqrt(1 - sin_a * sin_a);
  const double lag = sin_a < s_.sin_tip ? s_.lag_tip : s_.tool->lag_sc(sin_a, cos_a);
  return {false, phase(tooth, t, lag, p.x(), p.y()), INFINITY, rho, lag};
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
  if (s_.ringed) {  // a vertical axis: the profile over the node
    const double rho = std::sqrt(r2);
    if (!(rho < s_.profile.reach())) return false;
    const CutterProfile::Point p = s_.profile.at(rho);
    t = t1;
    q = {p.on && rho >= rho_lo_ && rho <= rho_hi_, 0.0,
         p.on ? c.z() - p.depth + s_.profile.up() : INFINITY, rho, q.lag + dt * lag_rate};
    return true;
  }
  if (!(r2 < s_.R2)) return false;
  const double below = std::sqrt(s_.R2 - r2);
  // The ball point through the frame map (land() is refused on a turning frame: it is fixed).
  const Vec3 p = tilted_ ? Vec3(to_tool_ * Vec3(dx, dy, -below)) : Vec3(dx, dy, -below);
  const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
  const bool over = p.z() <= 0 && rho >= rho_lo_ && rho <= rho_hi_;
  t = t1;
  q = {over, 0.0, c.z() - below, rho, q.lag + lag_rate * dt};
  return true;
}

double PassageGeometry::rate(const Sample& at, const Vec3& dv, double* lag_rate) const {
  // The moving point through the frame map, and its velocity: the node's offset q from the axis
  // (q' = -v) for a vertical tool, the ball point over the node in the tool frame for a tilted one.
  Vec3 p, dp;
  if (tilted_) {
    if (!lifted(at.t, at.c, at.v + dv, p, dp)) return NAN;
  } else {
    const Vec3 v = at.v + dv;
    p = Vec3(x_ - at.c.x(), y_ - at.c.y(), 0.0), dp = Vec3(-v.x(), -v.y(), 0.0);
  }
  const double r2 = p.x() * p.x() + p.y() * p.y();
  if (!(r2 > 0)) return NAN;
  // u' = (p . p') / r2 (u = ln rho), az' = (p x p') / r2.
  const double du = (p.x() * dp.x() + p.y() * dp.y()) / r2,
               daz = (p.x() * dp.y() - p.y() * dp.x()) / r2;
  if (s_.ringed) {  // a vertical axis: the lag's slope from the profile
    const double rho = std::sqrt(r2);
    if (!(rho < s_.profile.reach())) return NAN;
    const double lag = s_.profile.slope(*s_.tool, rho, s_.profile.at(rho)) * du;
    if (lag_rate) *lag_rate = lag;
    return s_.omega + lag - daz;
  }
  const double sin_a = std::sqrt(r2) / s_.R;
  if (sin_a >= 1) return NAN;
  // The polar angle's cosine: the ball point's depth in the tool frame (from the sine where the
  // frame is the workpiece's).
  const double cos_a = tilted_ ? std::abs(p.z()) / s_.R : std::sqrt(1 - sin_a * sin_a);
  const double lag = s_.lag_shape.slope(sin_a, cos_a, *s_.tool) * du;
  if (lag_rate) *lag_rate = lag;
  return s_.omega + lag - daz;
}

}  // namespace topomill::plugins
