// The paper's workpiece (Eq. 8-12): a convex cylinder of radius r, axis along X.
#include <cmath>

#include "topomill/plugin.hpp"
#include "topomill/surface_shape.hpp"

namespace topomill::plugins {

// Centre M at (y, z) = (0, -r) so that the crown (lambda = 0) is at the origin.
class ConvexArc : public SurfaceShape {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("radius", "Curvature radius r of the cross-section (the paper does not give it)")
        .with_unit("mm")
        .above(0)
        .at_most(1e6)
        .is_required();
    return s;
  }
  explicit ConvexArc(const Params& p) : r_(p.number("radius")) {}

  double height(double y) const override { return std::sqrt(r_ * r_ - y * y) - r_; }
  double inclination(double y) const override { return std::asin(y / r_); }
  double y_at_inclination(double lambda) const override { return r_ * std::sin(lambda); }
  double curvature_radius() const override { return r_; }
  double normal_residual(double y, double z, double depth) const override {
    return std::sqrt(y * y + (z + r_) * (z + r_)) - (r_ - depth);
  }
  double arc_coordinate(double y, double z) const override { return r_ * std::atan2(y, z + r_); }
  double y_min() const override { return -r_; }
  double y_max() const override { return r_; }

 private:
  double r_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("convex_arc", "0.1.0") {
  registrar.add<topomill::SurfaceShape, topomill::plugins::ConvexArc>(
      "convex_arc", "Convex cylindrical workpiece, axis along X (Hao et al. Eq. 8-12)");
}
