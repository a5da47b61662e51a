#include "topomill/tool_path.hpp"

#include "topomill/path_model.hpp"

#include "ring_rest.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace topomill {

ToolPath::ToolPath(std::shared_ptr<const SurfaceShape> surface, double offset, double feed_speed,
                   double spindle_rate, std::vector<Pass> passes)
    : surface_(std::move(surface)),
      offset_(offset),
      feed_speed_(feed_speed),
      spindle_rate_(spindle_rate),
      passes_(std::move(passes)),
      axis_(FeedAxis::Y),
      corrections_(passes_.size()) {
  bool along_y = false, along_x = false, other = false, lines_x = false, lines_y = false;
  timing_.resize(passes_.size());
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    if (!passes_[p].waypoints.empty()) set_waypoint_pass(p);
    Pass& pass = passes_[p];
    // The phase matters only modulo a turn, and the evaluators' walks count turns from it: kept
    // within one (at a start_angle of 1e300 deg tooth_passage would index turns past any
    // integer).
    // fmod is exact and leaves a phase within a turn as it was.
    pass.phase = std::fmod(pass.phase, 2 * M_PI);
    // Along the normal the axis turns only where the normal does: over the curvature (a pass
    // along Y on a curved surface); along X, or on a plane, its frame is fixed.
    if (pass.posture.normal)
      pass.posture.turns = pass.dy != 0 && std::isfinite(surface_->curvature_radius());
    const bool y = pass.dx == 0 && std::abs(pass.dy) == 1,
               x = pass.dy == 0 && std::abs(pass.dx) == 1;
    if (!x && !y && pass.waypoints.empty())
      throw std::invalid_argument("a pass's feed direction (" + std::to_string(pass.dx) + ", " +
                                  std::to_string(pass.dy) + ") is not along X or Y");
    along_y = along_y || y, along_x = along_x || x, other = other || (!x && !y);
    const bool line = pass.waypoints.empty();
    lines_x = lines_x || (line && x), lines_y = lines_y || (line && y);
    vertical_ = vertical_ && pass.posture.vertical();
  }
  // Lines from a path model all go one way (waypoints may go any).
  if (lines_x && lines_y) throw std::invalid_argument("passes feed along both X and Y");
  axis_ = other || (along_x && along_y) ? FeedAxis::None : along_x ? FeedAxis::X : FeedAxis::Y;
  for (std::size_t p = 0; p < passes_.size(); ++p)
    fixed_frame_.push_back(passes_[p].posture.fixed() ? frame_of(axis_of(p, 0.0))
                                                      : Eigen::Matrix3d::Identity());
}

// Times from the speeds (a segment's length over its speed: the raster written as waypoints
// along Y at the feed speed gets the raster's times and centres to the bit), foot points for the
// inclination, and whether the pass is a straight line along X or Y at one speed (dx, dy) and
// whether its axis turns.
void ToolPath::set_waypoint_pass(std::size_t p) {
  Pass& pass = passes_[p];
  const auto& w = pass.waypoints;
  if (w.size() < 2) throw std::invalid_argument("a pass of waypoints has fewer than two");
  Timing& tm = timing_[p];
  tm.t.assign(1, 0.0);
  Vec3 first_unit = Vec3::Zero();
  bool straight = true;
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    const Vec3 d = w[k + 1].centre - w[k].centre;
    const double len = d.norm();
    if (!(len > 0) || !(w[k].speed > 0))
      throw std::invalid_argument("waypoints " + std::to_string(k) + " and " +
                                  std::to_string(k + 1) + " of a pass do not move the tool");
    tm.unit.push_back(d / len);
    tm.t.push_back(tm.t.back() + len / w[k].speed);
    if (k == 0) first_unit = tm.unit.back();
    // Collinear to round-off (a line written as several points): still one line.
    straight = straight && (tm.unit.back() - first_unit).norm() < 1e-12 &&
               std::abs(w[k].speed - w[0].speed) <= 1e-12 * w[0].speed;
  }
  for (const Waypoint& q : w) {
    // The foot point, searched over a span that holds it wherever the centre is (bisection).
    const double s = surface_->arc_coordinate(q.centre.y(), q.centre.z());
    const double span = std::abs(q.centre.y()) + std::abs(q.centre.z()) + offset_ + 1.0;
    tm.foot_y.push_back(y_at_arc(*surface_, s, q.centre.y(), span));
    pass.posture.turns = pass.posture.turns || q.axis != w[0].axis;
  }
  pass.t_end = tm.t.back();
  pass.x = w[0].centre.x(), pass.y_start = tm.foot_y[0];
  // A straight line along X or Y in plan (it may climb or descend: an inclined plane), to
  // round-off: points computed by another program (a centre less its runout) can differ across
  // the line by an ulp, 1e-16 of a step, which no evaluator can see.
  const Vec3& u = first_unit;
  constexpr double kAcross = 1e-12;
  const bool line_x = straight && std::abs(u.y()) <= kAcross && u.x() != 0,
             line_y = straight && std::abs(u.x()) <= kAcross && u.y() != 0;
  pass.dx = line_x ? std::copysign(1.0, u.x()) : 0.0;
  pass.dy = line_y ? std::copysign(1.0, u.y()) : 0.0;
}

std::size_t ToolPath::segment(std::size_t p, double t) const {
  const std::vector<double>& ts = timing_[p].t;
  const auto after = std::upper_bound(ts.begin(), ts.end(), t) - ts.begin();
  return static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(after - 1, 0, static_cast<std::ptrdiff_t>(ts.size()) - 2));
}

double ToolPath::fraction(std::size_t p, std::size_t k, double t) const {
  const std::vector<double>& ts = timing_[p].t;
  return std::clamp((t - ts[k]) / (ts[k + 1] - ts[k]), 0.0, 1.0);
}

// The direction's components are 0 or +-1 (checked above), so that vf (d t) is vf t, -vf t or 0
// exactly: a forward pass along Y gives the bits it gave before passes had a direction.
double ToolPath::surface_y(std::size_t p, double t) const {
  if (!passes_[p].waypoints.empty()) {
    const std::size_t k = segment(p, t);
    const std::vector<double>& y = timing_[p].foot_y;
    return y[k] + fraction(p, k, t) * (y[k + 1] - y[k]);
  }
  return passes_[p].y_start + feed_speed_ * (passes_[p].dy * t);
}

// The surface's tangent over the plan direction (dx, dy): (dx, dy cos, -dy sin), a unit vector.
Vec3 ToolPath::feed_direction(std::size_t p, double t) const {
  const Pass& pass = passes_[p];
  if (!pass.waypoints.empty()) return timing_[p].unit[segment(p, t)];
  if (pass.dy == 0) return {pass.dx, 0.0, 0.0};
  const double lambda = surface_->inclination(surface_y(p, t));
  return {0.0, pass.dy * std::cos(lambda), -(pass.dy * std::sin(lambda))};
}

Vec3 ToolPath::nominal_centre(std::size_t p, double t) const {
  if (!passes_[p].waypoints.empty()) {
    // Along the segment holding t, and the first or last one's line beyond the ends (evaluators
    // look a little past them, as along a line pass).
    const std::size_t k = segment(p, t);
    const Waypoint& w = passes_[p].waypoints[k];
    Vec3 c = w.centre + timing_[p].unit[k] * (w.speed * (t - timing_[p].t[k]));
    if (runout_.offset > 0) c += runout_offset(p, t);
    return c;
  }
  const double y = surface_y(p, t);
  const double lambda = surface_->inclination(y);
  const double x = passes_[p].x + feed_speed_ * (passes_[p].dx * t);
  const double sl = std::sin(lambda), cl = std::cos(lambda);
  const double off = ring_ > 0 ? ring_distance(p, t, y, sl, cl) : offset_;
  Vec3 k{x, y + off * sl, surface_->height(y) + off * cl};
  if (runout_.offset > 0) k += runout_offset(p, t);  // (none: not even a zero, so the bits stay)
  return k;
}

void ToolPath::set_ring(double c) {
  ring_ = c;
  // Along X the foot point and the axis stay put over a pass: its centre's distance is found once.
  ring_rest_.assign(passes_.size(), NAN);
  if (!(c > 0) || !std::isfinite(surface_->curvature_radius())) return;
  for (std::size_t p = 0; p < passes_.size(); ++p)
    if (passes_[p].waypoints.empty() && passes_[p].dy == 0)
      ring_rest_[p] = detail::ring_rest(*surface_, passes_[p].y_start, axis(p, 0.0), c, offset_);
}

double ToolPath::ring_distance(std::size_t p, double t, double y, double sl, double cl) const {
  // On a plane the tangent plane is the surface: its closed form (ring_rest.hpp).
  if (!std::isfinite(surface_->curvature_radius())) {
    double off = offset_;
    const Vec3 n(0.0, sl, cl);
    off += ring_ * (passes_[p].posture.vertical() ? std::abs(sl) : n.cross(axis(p, t)).norm());
    return off;
  }
  if (!std::isnan(ring_rest_[p])) return ring_rest_[p];
  return detail::ring_rest(*surface_, y, axis(p, t), ring_, offset_);
}

Vec3 ToolPath::runout_offset(std::size_t p, double t) const {
  if (!(runout_.offset > 0)) return Vec3::Zero();
  const double a = spindle_angle(p, t) + runout_.angle;
  const Vec3 local(runout_.offset * std::cos(a), runout_.offset * std::sin(a), 0.0);
  return vertical_ ? local : Vec3(tool_frame(p, t) * local);
}

Vec3 ToolPath::axis(std::size_t p, double t) const {
  return passes_[p].posture.fixed() ? Vec3(fixed_frame_[p].col(2)) : axis_of(p, t);
}

Vec3 ToolPath::axis_of(std::size_t p, double t) const {
  const Pass& pass = passes_[p];
  const Posture& q = pass.posture;
  if (q.vertical()) return Vec3::UnitZ();
  if (q.given) {
    const std::size_t k = segment(p, t);
    const Vec3 &a = pass.waypoints[k].axis, &b = pass.waypoints[k + 1].axis;
    return a == b ? a : Vec3((a + fraction(p, k, t) * (b - a)).normalized());
  }
  const double cl = std::cos(q.lead), sl = std::sin(q.lead), ct = std::cos(q.tilt),
               st = std::sin(q.tilt);
  if (!q.normal) {
    // Fixed: about the pass's feed in plan F and C = F x Z.
    const Vec3 F(pass.dx, pass.dy, 0.0), C(pass.dy, -pass.dx, 0.0);
    return (ct * (cl * Vec3::UnitZ() + sl * F) + st * C).normalized();
  }
  // Normal: about the outward normal n at the contact point, the feed f along the surface and
  // c = f x n.
  const double lambda = surface_->inclination(surface_y(p, t));
  const Vec3 n(0.0, std::sin(lambda), std::cos(lambda)), f = feed_direction(p, t);
  return (ct * (cl * n + sl * f) + st * f.cross(n)).normalized();
}

Eigen::Matrix3d ToolPath::tool_frame(std::size_t p, double t) const {
  return passes_[p].posture.fixed() ? fixed_frame_[p] : frame_of(axis_of(p, t));
}

Eigen::Matrix3d ToolPath::frame_of(const Vec3& a) {
  const Vec3 x = (Vec3::UnitX() - a.x() * a).normalized();  // a is kept off X (layout)
  Eigen::Matrix3d q;
  q.col(0) = x, q.col(1) = a.cross(x), q.col(2) = a;
  return q;
}

double ToolPath::contact_angle(std::size_t p, double t) const {
  const double lambda = surface_->inclination(surface_y(p, t));
  if (passes_[p].posture.vertical()) return std::abs(lambda);
  const Vec3 n(0.0, std::sin(lambda), std::cos(lambda));
  return std::acos(std::clamp(n.dot(axis(p, t)), -1.0, 1.0));
}

Vec3 ToolPath::correction(std::size_t p, double t) const {
  return corrections_[p].at(t);
}

Vec3 ToolPath::centre(std::size_t p, double t) const {
  return corrected_ ? Vec3(nominal_centre(p, t) + correction(p, t)) : nominal_centre(p, t);
}

void ToolPath::set_correction(std::size_t p, double dt, std::vector<Vec3> samples) {
  for (const auto& v : samples)
    max_correction_ = std::max(max_correction_, v.cwiseAbs().maxCoeff());
  corrections_[p] = Correction{dt, std::move(samples)};
  corrected_ = true;
}

}  // namespace topomill
