#include "topomill/tool_path.hpp"

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
  bool along_y = false, along_x = false;
  for (const Pass& p : passes_) {
    const bool y = p.dx == 0 && std::abs(p.dy) == 1, x = p.dy == 0 && std::abs(p.dx) == 1;
    if (!x && !y)
      throw std::invalid_argument("a pass's feed direction (" + std::to_string(p.dx) + ", " +
                                  std::to_string(p.dy) + ") is not along X or Y");
    along_y = along_y || y, along_x = along_x || x;
    vertical_ = vertical_ && p.posture.vertical();
  }
  if (along_x && along_y) throw std::invalid_argument("passes feed along both X and Y");
  if (along_x) axis_ = FeedAxis::X;
  for (std::size_t p = 0; p < passes_.size(); ++p)
    fixed_frame_.push_back(passes_[p].posture.normal ? Eigen::Matrix3d::Identity()
                                                     : frame_of(axis_of(p, 0.0)));
}

// The direction's components are 0 or +-1 (checked above), so that vf (d t) is vf t, -vf t or 0
// exactly: a forward pass along Y gives the bits it gave before passes had a direction.
double ToolPath::surface_y(std::size_t p, double t) const {
  return passes_[p].y_start + feed_speed_ * (passes_[p].dy * t);
}

// The surface's tangent over the plan direction (dx, dy): (dx, dy cos, -dy sin), a unit vector.
Vec3 ToolPath::feed_direction(std::size_t p, double t) const {
  const Pass& pass = passes_[p];
  if (pass.dy == 0) return {pass.dx, 0.0, 0.0};
  const double lambda = surface_->inclination(surface_y(p, t));
  return {0.0, pass.dy * std::cos(lambda), -(pass.dy * std::sin(lambda))};
}

Vec3 ToolPath::nominal_centre(std::size_t p, double t) const {
  const double y = surface_y(p, t);
  const double lambda = surface_->inclination(y);
  const double x = passes_[p].x + feed_speed_ * (passes_[p].dx * t);
  Vec3 k{x, y + offset_ * std::sin(lambda), surface_->height(y) + offset_ * std::cos(lambda)};
  if (runout_.offset > 0) k += runout_offset(p, t);  // (none: not even a zero, so the bits stay)
  return k;
}

Vec3 ToolPath::runout_offset(std::size_t p, double t) const {
  if (!(runout_.offset > 0)) return Vec3::Zero();
  const double a = spindle_angle(p, t) + runout_.angle;
  const Vec3 local(runout_.offset * std::cos(a), runout_.offset * std::sin(a), 0.0);
  return vertical_ ? local : Vec3(tool_frame(p, t) * local);
}

Vec3 ToolPath::axis(std::size_t p, double t) const {
  return passes_[p].posture.normal ? axis_of(p, t) : Vec3(fixed_frame_[p].col(2));
}

Vec3 ToolPath::axis_of(std::size_t p, double t) const {
  const Pass& pass = passes_[p];
  const Posture& q = pass.posture;
  if (q.vertical()) return Vec3::UnitZ();
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
  return passes_[p].posture.normal ? frame_of(axis_of(p, t)) : fixed_frame_[p];
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
