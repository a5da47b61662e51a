// Mechanistic ball-end cutting force (Armarego; Lee and Altintas form), MODEL.md Eq. 18-21.
#include <cmath>

#include "topomill/force_model.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Each edge element at polar angle alpha and azimuth phi has the outward ball normal
// n = (sin a cos phi, sin a sin phi, -cos a), the meridian tangent a = dn/d(alpha) =
// (cos a cos phi, cos a sin phi, sin a) and the cutting direction v = s (-sin phi, cos phi, 0)
// (s = +1 counter-clockwise). Its force on the tool is -dFt v - dFr n - dFa a: Eq. 20 in these
// vectors, which reproduces MODEL.md's closed form (tested). Chip thickness t = max(0, fz f.n).
// Elements count when they face the feed (t > 0), lie in the CATW and, when the core says so
// (CutState::in_material), are in material: below the uncut surface, not removed by the
// previous pass.
class Armarego : public ForceModel {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("Ktc", "Tangential cutting coefficient").with_unit("N/mm^2").with_default(1512.8);
    s.add_number("Krc", "Radial cutting coefficient").with_unit("N/mm^2").with_default(656.8);
    s.add_number("Kac", "Axial cutting coefficient").with_unit("N/mm^2").with_default(-1123.4);
    s.add_number("Kte", "Tangential edge coefficient").with_unit("N/mm").with_default(198.5);
    s.add_number("Kre", "Radial edge coefficient").with_unit("N/mm").with_default(110.1);
    s.add_number("Kae", "Axial edge coefficient").with_unit("N/mm").with_default(-42.4);
    s.add_integer("elements", "Edge elements over the engaged polar-angle range, per tooth")
        .at_least(1)
        .at_most(100000)
        .with_default(std::int64_t{200});
    return s;
  }
  explicit Armarego(const Params& p)
      : ktc_(p.number("Ktc")),
        krc_(p.number("Krc")),
        kac_(p.number("Kac")),
        kte_(p.number("Kte")),
        kre_(p.number("Kre")),
        kae_(p.number("Kae")),
        elements_(static_cast<int>(p.integer("elements"))) {}

  CuttingForce evaluate(const ToolGeometry& tool, const CutState& st) const override {
    const double R = tool.radius();
    const double da = (st.alpha_max - st.alpha_min) / elements_;
    const double sense = st.spindle_rate >= 0 ? 1.0 : -1.0;
    CuttingForce out;
    double weight = 0, moment = 0;
    for (int j = 0; j < tool.teeth(); ++j) {
      for (int e = 0; e < elements_; ++e) {
        const double a = st.alpha_min + (e + 0.5) * da;  // midpoint rule
        const double phi =
            tool.tooth_angle(j) + tool.lag(std::max(a, tool.min_polar_angle())) + st.spindle_angle;
        const double sa = std::sin(a), ca = std::cos(a), sp = std::sin(phi), cp = std::cos(phi);
        const Vec3 n(sa * cp, sa * sp, -ca), m(ca * cp, ca * sp, sa), v(-sense * sp, sense * cp, 0);
        const double t = st.feed_per_tooth * st.feed_direction.dot(n);
        if (t <= 0) continue;  // not in cut: the element faces away from the feed
        if (st.in_material && !st.in_material(R * n)) continue;  // air: above or already cut
        const double db = R * da;
        const double slope = sa * tool.lag_slope(std::max(a, tool.min_polar_angle()));
        const double ds = db * std::sqrt(1 + slope * slope);
        const double ft = kte_ * ds + ktc_ * t * db, fr = kre_ * ds + krc_ * t * db,
                     fa = kae_ * ds + kac_ * t * db;
        const Vec3 f = -ft * v - fr * n - fa * m;
        out.force += f;
        const double w = f.norm();
        weight += w;
        moment += w * R * (1 - ca);  // height of the element above the tip
      }
    }
    out.load_centre = weight > 0 ? moment / weight : 0.0;
    return out;
  }

 private:
  double ktc_, krc_, kac_, kte_, kre_, kae_;
  int elements_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("armarego", "0.1.0") {
  registrar.add<topomill::ForceModel, topomill::plugins::Armarego>(
      "armarego",
      "Mechanistic ball-end force, Armarego/Lee-Altintas (Eq. 18-21); defaults: "
      "Table 3 of Hao et al.");
}
