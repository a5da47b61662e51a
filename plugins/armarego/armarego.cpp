// Mechanistic ball-end cutting force (Armarego; Lee and Altintas form), MODEL.md Eq. 18-21.
#include <cmath>
#include <vector>

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

  // Per element the polar angle's sine and cosine (stepped by rotation), the lag and its
  // sine and cosine are shared by all teeth; each tooth's azimuth is then a rotation of its own
  // angle at this instant, so a sample costs the lag (a log for the loxodrome) and one sincos
  // per element, not a sincos, a tan, a log, a sin and a sincos per element and tooth.
  CuttingForce evaluate(const ToolGeometry& tool, const CutState& st) const override {
    const double R = tool.radius();
    const double da = (st.alpha_max - st.alpha_min) / elements_;
    const double sense = st.spindle_rate >= 0 ? 1.0 : -1.0;
    const double tip = tool.min_polar_angle(), lag_tip = tool.lag(tip),
                 slope_tip = tool.lag_slope(tip);
    const int teeth = tool.teeth();
    std::vector<double> tooth_cos(static_cast<std::size_t>(teeth)), tooth_sin(tooth_cos.size());
    for (int j = 0; j < teeth; ++j) {
      const double angle = tool.tooth_angle(j) + st.spindle_angle;
      tooth_cos[static_cast<std::size_t>(j)] = std::cos(angle);
      tooth_sin[static_cast<std::size_t>(j)] = std::sin(angle);
    }
    const double a0 = st.alpha_min + 0.5 * da;  // midpoint rule
    const double step_c = std::cos(da), step_s = std::sin(da);
    double sa = std::sin(a0), ca = std::cos(a0);
    CuttingForce out;
    double weight = 0, moment = 0;
    for (int e = 0; e < elements_; ++e) {
      if (e > 0) {
        const double s_next = sa * step_c + ca * step_s;
        ca = ca * step_c - sa * step_s, sa = s_next;
      }
      const double a = a0 + e * da;
      const bool held = a < tip;  // the tip's stretch, where the lag is held
      const double lag = held ? lag_tip : tool.lag_sc(sa, ca);
      const double cl = std::cos(lag), sl = std::sin(lag);
      const double db = R * da;
      const double slope = sa * (held ? slope_tip : tool.lag_slope_sc(sa, ca));
      const double ds = db * std::sqrt(1 + slope * slope);
      for (std::size_t j = 0; j < tooth_cos.size(); ++j) {
        const double cp = tooth_cos[j] * cl - tooth_sin[j] * sl;
        const double sp = tooth_sin[j] * cl + tooth_cos[j] * sl;
        const Vec3 n(sa * cp, sa * sp, -ca), m(ca * cp, ca * sp, sa), v(-sense * sp, sense * cp, 0);
        const double t = st.feed_per_tooth * st.feed_direction.dot(n);
        if (t <= 0) continue;  // not in cut: the element faces away from the feed
        if (st.in_material && !st.in_material(R * n)) continue;  // air: above or already cut
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
