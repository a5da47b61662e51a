// Face mill with round inserts: N inserts of radius ri whose centres lie on the circle of
// diameter D, as in Wang et al. (2023) and the two open simulators built on it (surf-topo, TIDE).
// Each insert's edge lies in a half-plane through the axis turned by the radial rake gamma_f;
// the axial rake gamma_p tilts the insert in that half-plane: a point l = ri sin(alpha) along
// the insert and z = ri (1 - cos(alpha)) above its lowest point lies at distance
// D/2 + l + z sin(gamma_p) from the axis, z cos(gamma_p) above the lowest point (docs/model.md,
// "Cutters": the projects' definition, stated with a sketch).
#include <cmath>

#include "../common/cutter_schema.hpp"
#include "topomill/plugin.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class RoundInsert : public ToolGeometry {
 public:
  static constexpr double kDeg = M_PI / 180.0;
  static Schema schema() {
    Schema s;
    s.add_number("diameter", "Diameter D of the circle through the inserts' centres")
        .with_unit("mm")
        .above(0)
        .at_most(2000)
        .is_required();
    s.add_number("insert_radius", "Radius ri of the round inserts")
        .with_unit("mm")
        .above(0)
        .at_most(100)
        .is_required();
    add_teeth(s, "Number of inserts N, evenly spaced");
    s.add_number("radial_rake", "Radial rake gamma_f: the insert's half-plane turned about +Z")
        .with_unit("deg")
        .at_least(-45)
        .at_most(45)
        .with_default(0.0);
    s.add_number("axial_rake", "Axial rake gamma_p: the insert tilted in its half-plane")
        .with_unit("deg")
        .at_least(-45)
        .at_most(45)
        .with_default(0.0);
    return s;
  }

  explicit RoundInsert(const Params& p)
      : centre_(p.number("diameter") / 2),
        ri_(p.number("insert_radius")),
        teeth_(static_cast<int>(p.integer("teeth"))),
        radial_(p.number("radial_rake") * kDeg),
        sin_p_(std::sin(p.number("axial_rake") * kDeg)),
        cos_p_(std::cos(p.number("axial_rake") * kDeg)),
        first_(first_angle()) {}

  double radius() const override { return ri_; }
  int teeth() const override { return teeth_; }
  double ring() const override { return centre_; }
  double first_polar_angle() const override { return first_; }
  // The edge lies in its half-plane: the same azimuth all along.
  double lag(double) const override { return radial_; }
  double lag_sc(double, double) const override { return radial_; }
  double lag_slope(double) const override { return 0.0; }
  double lag_slope_sc(double, double) const override { return 0.0; }
  Vec2 section(double alpha) const override {
    const double up = ri_ * (1 - std::cos(alpha));  // above the insert's lowest point
    return {centre_ + ri_ * std::sin(alpha) + up * sin_p_, -ri_ + up * cos_p_};
  }
  // With a negative axial rake the edge folds back before alpha = pi/2: its widest, where
  // d/dalpha of sin(alpha) + (1 - cos(alpha)) sin(gamma_p) vanishes, is sin(gamma_p) +
  // sqrt(1 + sin(gamma_p)^2) out from the insert's centre (in ri).
  double reach() const override {
    if (sin_p_ >= 0) return section(M_PI / 2).x();
    return centre_ + ri_ * (sin_p_ + std::sqrt(1 + sin_p_ * sin_p_));
  }

 private:
  // The inner end of the edge: -pi/2, or where the insert reaches the axis (a large insert on a
  // small circle), found by halving between a sample inside and one past the axis.
  double first_angle() const {
    constexpr int kSamples = 1024;
    double inside = 0.0;
    for (int k = 1; k <= kSamples; ++k) {
      const double a = -M_PI / 2 * k / kSamples;
      if (section(a).x() < 0) {
        double past = a;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (inside + past);
          (section(mid).x() < 0 ? past : inside) = mid;
        }
        return inside;
      }
      inside = a;
    }
    return -M_PI / 2;
  }

  double centre_, ri_;
  int teeth_;
  double radial_, sin_p_, cos_p_, first_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("round_insert", "0.1.0") {
  registrar.add<topomill::ToolGeometry, topomill::plugins::RoundInsert>(
      "round_insert",
      "Face mill with round inserts of radius ri on the circle of diameter D, radial and axial "
      "rake (Wang et al. 2023)");
}
