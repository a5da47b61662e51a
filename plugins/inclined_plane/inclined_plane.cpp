// A plane of constant inclination: the closed-form reference case (scallops are exact here).
#include <cmath>

#include "topomill/error.hpp"
#include "topomill/plugin.hpp"
#include "topomill/surface_shape.hpp"

namespace topomill::plugins {

// Normal (0, sin lambda, cos lambda) everywhere: z = -y tan(lambda), through the origin.
class InclinedPlane : public SurfaceShape {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("angle",
                 "Inclination lambda of the normal from +Z towards +Y; the region's "
                 "lambda must be the same")
        .with_unit("deg")
        .above(-90)
        .below(90)
        .with_default(0.0);
    return s;
  }
  explicit InclinedPlane(const Params& p)
      : lambda_(p.number("angle") * M_PI / 180.0), s_(std::sin(lambda_)), c_(std::cos(lambda_)) {}

  double height(double y) const override { return -y * s_ / c_; }
  double inclination(double) const override { return lambda_; }
  double y_at_inclination(double lambda) const override {
    if (std::abs(lambda - lambda_) > 1e-9)
      throw ParamError("angle", "a plane inclined at " + format_number(lambda_ * 180 / M_PI) +
                                    " deg has no point whose normal is at " +
                                    format_number(lambda * 180 / M_PI) +
                                    " deg: set region.lambda to the plane's angle");
    return 0.0;
  }
  double curvature_radius() const override { return kFlat; }
  double normal_residual(double y, double z, double depth) const override {
    return y * s_ + z * c_ + depth;
  }
  double arc_coordinate(double y, double z) const override { return y * c_ - z * s_; }

 private:
  double lambda_, s_, c_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("inclined_plane", "0.1.0") {
  registrar.add<topomill::SurfaceShape, topomill::plugins::InclinedPlane>(
      "inclined_plane", "Plane of constant inclination lambda (closed-form checks)");
}
