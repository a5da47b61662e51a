#include "topomill/tool_path.hpp"

#include <algorithm>
#include <cmath>

namespace topomill {

ToolPath::ToolPath(std::shared_ptr<const SurfaceShape> surface, double offset, double feed_speed,
                   double spindle_rate, std::vector<Pass> passes, FeedAxis axis)
    : surface_(std::move(surface)),
      offset_(offset),
      feed_speed_(feed_speed),
      spindle_rate_(spindle_rate),
      passes_(std::move(passes)),
      axis_(axis),
      corrections_(passes_.size()) {}

double ToolPath::surface_y(std::size_t p, double t) const {
  return axis_ == FeedAxis::Y ? passes_[p].y_start + feed_speed_ * t : passes_[p].y_start;
}

Vec3 ToolPath::feed_direction(std::size_t p, double t) const {
  if (axis_ == FeedAxis::X) return Vec3::UnitX();
  const double lambda = surface_->inclination(surface_y(p, t));
  return {0.0, std::cos(lambda), -std::sin(lambda)};
}

Vec3 ToolPath::nominal_centre(std::size_t p, double t) const {
  const double y = surface_y(p, t);
  const double lambda = surface_->inclination(y);
  const double x = axis_ == FeedAxis::X ? passes_[p].x + feed_speed_ * t : passes_[p].x;
  return {x, y + offset_ * std::sin(lambda), surface_->height(y) + offset_ * std::cos(lambda)};
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
