#include "passage_setup.hpp"

#include <algorithm>

#include "topomill/interrupt.hpp"

namespace topomill::plugins {

namespace {
// Interpolated centres agree with the path to a nanometre's tenth: far below any grid.
constexpr double kTableTolerance = 1e-7;  // mm
// A nominal height that bends down by no more than this over a window (round-off on a plane)
// leaves the floor a single minimum for every purpose the walks have.
constexpr double kBendNegligible = 1e-10;  // mm
// Windows tabulated between two looks at the stop flag, less one (a mask).
constexpr std::size_t kWindowsPerStopCheck = 1023;

// A bent pass's windows: runs of segments collinear to round-off at one speed (the criterion
// ToolPath uses for a whole pass), so that a line written as many points stays one window. Where
// the data's axis turns, each segment is a window of its own: its frame turns smoothly only
// between its two points (BlendFrame).
std::vector<PassageSetup::Extent> windows_of(const ToolPath& path, std::size_t p) {
  const ToolPath::Pass& pass = path.pass(p);
  const bool turns = pass.posture.given && pass.posture.turns;
  const bool line = pass.waypoints.empty() || ((pass.dx != 0 || pass.dy != 0) && !turns);
  if (line) return {{p, 0.0, pass.t_end, 0}};
  std::vector<PassageSetup::Extent> out;
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

// The table's refusal, out of line (centre_table.hpp says why).
void CentreTable::refuse(const Midpoint& worst) const {
  const double y = path_->surface_y(pass_, worst.t);
  throw ParamError(
      "plugin", "tooth_passage follows smooth centre paths only, and the cutter's centre on pass " +
                    std::to_string(pass_ + 1) +
                    (std::isfinite(worst.error)
                         ? " turns a corner near y = " + format_number(y) +
                               " mm (as a ringed cutter resting on both walls of a concave "
                               "surface does)"
                         : " is not defined near y = " + format_number(y) +
                               " mm (the path leaves the surface there)") +
                    ": expected evaluator.plugin = \"zmap\", which follows any path");
}

PassageSetup::PassageSetup(const EvaluationRequest& rq, double margin_, int iterations_, int edge)
    : path(rq.path),
      tool(rq.tool),
      parallel(false),
      profile(edge < 0 ? CutterProfile(*rq.tool)
                       : CutterProfile(*rq.tool, edge * rq.path->runout().edge_radial,
                                       edge * rq.path->runout().edge_axial)),
      ringed(profile.ringed()),
      windowed(rq.tool->ring() == 0 && !rq.path->runout().per_edge()),
      R(rq.tool->radius()),
      R2(R * R),
      omega(rq.path->spindle_rate()),
      speed(INFINITY),
      rev(kTwoPi / std::abs(omega)),
      period(rev / (edge < 0 ? rq.tool->teeth() : 1)),
      reach(profile.reach() + rq.path->max_correction()),
      margin(margin_),
      kappa(rq.kappa),
      iterations(iterations_),
      teeth(edge < 0 ? rq.tool->teeth() : 1),
      along_y(rq.path->feed_axis() == ToolPath::FeedAxis::Y),
      stop(rq.stop),
      lag_shape(*rq.tool, profile),
      wiggles(rq.path->corrected() || rq.path->runout().offset > 0),
      runout(rq.path->runout().offset) {
  for (int j = 0; j < teeth; ++j) tooth_angle.push_back(tool->tooth_angle(edge < 0 ? j : edge));
  sin_tip = std::sin(tool->min_polar_angle());
  lag_tip = tool->lag(tool->min_polar_angle());
  std::vector<Extent> extents;
  for (std::size_t p = 0; p < path->passes(); ++p)
    for (const Extent& w : windows_of(*path, p)) extents.push_back(w);
  parallel = path->feed_axis() != ToolPath::FeedAxis::None && extents.size() == path->passes();
  // The lag's slope over the cutter.
  const double k1 = lag_shape.slope_to(ringed ? profile.rim_out(kRimFraction) : kRimFraction * R);
  gap_lag = std::sqrt(1 + k1 * k1);
  window.reserve(extents.size());
  std::shared_ptr<const CorrectionIndex> index;  // the pass's, shared by its windows
  for (const Extent& where : extents) {
    // Hundreds of thousands of windows take seconds to tabulate: a stop request is looked at.
    if (stop && (window.size() & kWindowsPerStopCheck) == 0 && stop->load()) throw Interrupted();
    if (!index || where.t_lo == 0)
      index = std::make_shared<const CorrectionIndex>(path->correction_samples(where.pass));
    add_window(where, index);
  }
  speed = std::max(speed, 1e-12);
}

void PassageSetup::add_window(const Extent& where,
                              const std::shared_ptr<const CorrectionIndex>& index) {
  const double pad = 2 * rev;  // a probe may look a revolution beyond either end of a window
  const std::size_t p = where.pass;
  const double t_lo = where.t_lo, t_hi = where.t_hi, t_mid = 0.5 * (t_lo + t_hi);
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
  window.emplace_back(
      where, CentreTable(*path, p, t_lo - pad, t_hi + pad, kTableTolerance, false, stretch, index));
  Window& win = window.back();
  if (runout > 0)
    win.spindle_axis.emplace(*path, p, t_lo - pad, t_hi + pad, kTableTolerance, true, stretch,
                             index);
  // A fixed posture keeps the frame over the pass; along the normal over the curvature it turns
  // about X with the inclination (tooth_passage.cpp says which postures are followed).
  const bool tilt = !path->pass(p).posture.vertical();
  win.tilted = tilt;
  win.to_tool = path->tool_frame(p, t_lo).transpose();
  win.turn = turn_bounds(*path, where, pad);
  const Vec3 axis = path->axis(p, t_lo);
  win.tip_offset = {tilt ? -R * axis.x() : 0.0, tilt ? -R * axis.y() : 0.0};
  const Vec3 c0 = path->nominal_centre(p, 0.0);
  win.line = along_y ? c0.x() : c0.y();
  // The correction is linear between its samples and held beyond: its range is theirs.
  const CorrectionBounds whole = win.centre.correction_bounds(-INFINITY, INFINITY);
  win.shift_lo = whole.lo - Vec3(runout, runout, 0),
  win.shift_hi = whole.hi + Vec3(runout, runout, 0);
  win.lowest_centre = win.centre.lowest_z(t_lo, t_hi);
  win.lowest_nominal = win.centre.nominal_lowest_z();
  win.nominal_speed = win.centre.top_speed();
  bound_window(win, whole.lo, whole.hi);
  bound_floor_tail(win);
}

void PassageSetup::bound_floor_tail(Window& win) const {
  if (!wiggles) return;
  const CentreTable& table = win.spindle_axis ? *win.spindle_axis : win.centre;
  const CentreTable::Bend b = table.z_bend();
  const double span = win.t_hi - win.t_lo;
  if (b.bend * span * span / 2 + b.jump * span <= kBendNegligible) return;
  FloorTail& f = win.tail;
  f.on = true, f.bend = b.bend, f.jump = b.jump;
  const Vec3 a = table.nominal(win.t_lo), e = table.nominal(win.t_hi);
  const double len = std::hypot(e.x() - a.x(), e.y() - a.y());
  f.x = a.x(), f.y = a.y();
  f.ux = len > 0 ? (e.x() - a.x()) / len : 1.0, f.uy = len > 0 ? (e.y() - a.y()) / len : 0.0;
  const CentreTable::LineSpeeds s = table.line_speeds(f.ux, f.uy);
  if (std::isfinite(s.along_lo) && std::isfinite(s.along_hi))
    f.along_lo = s.along_lo, f.along_hi = s.along_hi;
  f.off = table.plan_deviation(a, f.ux, f.uy) + 1e-12;
  // The box's farthest reach along (ax, ay).
  const Vec3 &lo = win.shift_lo, &hi = win.shift_hi;
  auto support = [&](double ax, double ay) {
    return std::max(ax * lo.x(), ax * hi.x()) + std::max(ay * lo.y(), ay * hi.y());
  };
  f.ahead = support(f.ux, f.uy), f.behind = support(-f.ux, -f.uy);
  f.side = std::max(support(-f.uy, f.ux), support(f.uy, -f.ux));
}

void PassageSetup::bound_window(Window& win, const Vec3& lo, const Vec3& hi) {
  const std::size_t p = win.pass;
  const double t_lo = win.t_lo, t_hi = win.t_hi;
  const double v = top_speed(window.size() - 1, -INFINITY, INFINITY).first, half = 0.5 * rev;
  win.gap_rho = {kRoom * (v * half + gap_lag * v / std::abs(omega)),
                 (ringed ? profile.rim_out(kRimFraction) : kRimFraction * R) - v * half};
  // The line from the window's nominal start to its end in plan; the correction's plan offset
  // at most its box's farthest corner.
  const Vec3 a = path->nominal_centre(p, t_lo), b = path->nominal_centre(p, t_hi);
  const double len = std::hypot(b.x() - a.x(), b.y() - a.y());
  const double sx = std::max(std::abs(lo.x()), std::abs(hi.x()));
  const double sy = std::max(std::abs(lo.y()), std::abs(hi.y()));
  PlanLine l{a.x(), a.y(), 0.0, 0.0, INFINITY, v};
  if (len > 0) {
    l.ux = (b.x() - a.x()) / len, l.uy = (b.y() - a.y()) / len;
    l.off = win.centre.plan_deviation(a, l.ux, l.uy) + std::hypot(sx, sy) + 1e-12;
    if (!wiggles && !win.tilted && !win.turn.on) {
      const CentreTable::LineSpeeds s = win.centre.line_speeds(l.ux, l.uy);
      if (s.along_lo > 0 && std::isfinite(s.along_hi))  // (not so for a table with no piece)
        l.along_lo = s.along_lo, l.speed_hi = std::hypot(s.along_hi, s.across_hi),
        l.across_hi = s.across_hi;
    }
  }
  win.plan_line = l;
  const Vec3 sa = a - path->runout_offset(p, t_lo), sb = b - path->runout_offset(p, t_hi);
  win.segment = {sa.x(), sa.y(), sb.x(), sb.y(), runout + std::hypot(sx, sy) + 1e-9};
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
      const double across = std::abs((along_y ? x : y) - window[w].line);
      if (across < reach) out.push_back({across, w});
    } else if (const double d = window[w].segment.distance(x, y) - window[w].segment.slack;
               d < profile.reach()) {
      // Every crossing lies on the cutter, no lower than its lowest centre less its depth at the
      // least distance the centre comes to in plan.
      const double depth = ringed ? profile.hull_depth(std::max(d, 0.0))
                                  : std::sqrt(R2 - std::pow(std::max(d, 0.0), 2));
      out.push_back({window[w].lowest_centre + profile.up() - depth, w});
    }
  }
  std::sort(out.begin(), out.end());
}

bool PassageSetup::on_tip_line(std::size_t w, double x, double y) const {
  if (parallel) return std::abs((along_y ? x : y) - tip_line(w)) < kOnAxis;
  if (window[w].turn.on) {
    // The tip's path bends as the frame turns: where the tip is level with the node, whether it
    // is over it (to a micrometre: tip_height then asks for kOnAxis).
    const double t = tip_time(w, x, y);
    if (!std::isfinite(t)) return false;
    const Vec3 tip = window[w].centre(t) - R * Vec3(to_tool_at(w, t).row(2).transpose());
    return std::hypot(tip.x() - x, tip.y() - y) < 1e-3;
  }
  const PlanLine& l = window[w].plan_line;
  const double dx = x - l.x - window[w].tip_offset.first,
               dy = y - l.y - window[w].tip_offset.second;
  return std::abs(l.ux * dy - l.uy * dx) < kOnAxis &&
         std::isfinite(l.off);  // a window that moves in plan
}

std::pair<double, double> PassageSetup::top_speed(std::size_t w, double ta, double tb) const {
  const auto [h, v] = window[w].nominal_speed;
  const CorrectionBounds c = window[w].centre.correction_bounds(ta, tb);
  return {h + c.speed_xy, v + c.speed_z};
}

PassageSetup::Turn PassageSetup::turn_bounds(const ToolPath& path, const Extent& w, double pad) {
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
  return path->surface().inclination(path->surface_y(window[w].pass, t)) - window[w].turn.lambda0;
}

double PassageSetup::turn_rate(std::size_t w, double t) const {
  const SurfaceShape& surface = path->surface();
  const std::size_t p = window[w].pass;
  const double y = path->surface_y(p, t), h = 1e-5;  // mm: theta' to about 1e-12 of itself
  return (surface.inclination(y + h) - surface.inclination(y - h)) / (2 * h) *
         (path->feed_speed() * path->pass(p).dy);
}

Eigen::Matrix3d PassageSetup::to_tool_at(std::size_t w, double t) const {
  const Window& win = window[w];
  if (!win.turn.on) return win.to_tool;
  if (win.turn.blend) return win.turn.frame.at(t).transpose();
  const double th = turn_angle(w, t), c = std::cos(th), s = std::sin(th);
  Eigen::Matrix3d r;  // R_x(theta): Q(t)^T = Q(0)^T R_x(theta)
  r << 1, 0, 0, 0, c, -s, 0, s, c;
  return win.to_tool * r;
}

double PassageSetup::level_time(std::size_t w, double x, double y) const {
  const double t_lo = window[w].t_lo, t_hi = window[w].t_hi;
  const ToolPath::Pass& pass = path->pass(window[w].pass);
  // Signed along the window's feed (a reversed pass feeds towards -Y or -X), so that it grows.
  const PlanLine& l = window[w].plan_line;
  const double sign = along_y ? pass.dy : pass.dx;
  auto along = [&](double t) {
    const Vec3 c = window[w].centre.nominal(t);
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

double PassageSetup::tip_time(std::size_t w, double x, double y) const {
  const Window& win = window[w];
  double t = level_time(w, x - win.tip_offset.first, y - win.tip_offset.second);
  // On a turning window the tip's offset turns with the frame (along the normal only along the
  // feed: a turn about X leaves R a_x as it was): a few steps of the level time at the offset
  // then.
  for (int k = 0; k < 4 && win.turn.on && std::isfinite(t); ++k) {
    const Vec3 a = to_tool_at(w, t).row(2).transpose();
    t = level_time(w, x + R * a.x(), y + R * a.y());
  }
  return t;
}

std::pair<double, double> PassageSetup::contact_radii(std::size_t w, double t) const {
  // The contact's polar angle about the axis: |lambda| for a vertical tool.
  const double lambda = path->contact_angle(window[w].pass, t);
  const double lo = std::max(0.0, lambda - margin * kappa);
  const double hi = std::min(M_PI / 2, lambda + margin * kappa);
  // A ringed cutter has no contact window (the paper's CATW is the ball's): all of its edge.
  // Nor has any edge a per-edge runout moved (zmap's choice: ZMap::windowed).
  if (!windowed) return {0.0, INFINITY};
  return {R * std::sin(lo), R * std::sin(hi)};
}

}  // namespace topomill::plugins
