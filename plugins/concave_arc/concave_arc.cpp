// A concave cylinder of radius r, axis along X: the mirror case of the paper's convex arc.
#include <cmath>

#include "topomill/plugin.hpp"
#include "topomill/surface_shape.hpp"

namespace topomill::plugins {

// Centre M at (y, z) = (0, r), above the surface, so that the bottom (lambda = 0) is at the
// origin. The outward normal points towards M: lambda = -asin(y / r).
class ConcaveArc : public SurfaceShape {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("radius", "Curvature radius r of the cross-section; must exceed the ball radius")
        .with_unit("mm")
        .above(0)
        .at_most(1e6)
        .is_required();
    return s;
  }
  explicit ConcaveArc(const Params& p) : r_(p.number("radius")) {}

  double height(double y) const override { return r_ - std::sqrt(r_ * r_ - y * y); }
  double inclination(double y) const override { return -std::asin(y / r_); }
  double y_at_inclination(double lambda) const override { return -r_ * std::sin(lambda); }
  double curvature_radius() const override { return -r_; }
  double normal_residual(double y, double z, double depth) const override {
    return (r_ + depth) - std::sqrt(y * y + (r_ - z) * (r_ - z));
  }
  double arc_coordinate(double y, double z) const override { return r_ * std::atan2(y, r_ - z); }
  double y_min() const override { return -r_; }
  double y_max() const override { return r_; }

 private:
  double r_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("concave_arc", "0.1.0") {
  registrar.add<topomill::SurfaceShape, topomill::plugins::ConcaveArc>(
      "concave_arc", "Concave cylindrical workpiece, axis along X");
}
