// Mechanistic ball-end cutting force (Armarego; Lee and Altintas form), docs/model.md Eq. 18-21.
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "topomill/force_model.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Each edge element at polar angle alpha and azimuth phi has the outward ball normal
// n = (sin a cos phi, sin a sin phi, -cos a), the meridian tangent a = dn/d(alpha) =
// (cos a cos phi, cos a sin phi, sin a) and the cutting direction v = s (-sin phi, cos phi, 0)
// (s = +1 counter-clockwise). Its force on the tool is -dFt v - dFr n - dFa a: Eq. 20 in these
// vectors, which reproduces docs/model.md's closed form (tested). Chip thickness t = max(0, fz
// f.n). Elements count when they face the feed (t > 0), lie in the CATW and, when the core says so
// (CutState::in_material), are in material: below the uncut surface, not removed by the
// previous pass.
class Armarego : public ForceModel {
 public:
  static Schema schema() {
    Schema s;
    // Table 3's values. Bounded far beyond any material (a few thousand N/mm^2) so that a typo
    // of 1e308 is refused at its key instead of overflowing the force.
    struct Coefficient {
      const char *name, *doc, *unit;
      double value, bound;
    };
    for (const Coefficient& c : {
             Coefficient{"Ktc", "Tangential cutting coefficient", "N/mm^2", 1512.8, 1e6},
             Coefficient{"Krc", "Radial cutting coefficient", "N/mm^2", 656.8, 1e6},
             Coefficient{"Kac", "Axial cutting coefficient", "N/mm^2", -1123.4, 1e6},
             Coefficient{"Kte", "Tangential edge coefficient", "N/mm", 198.5, 1e5},
             Coefficient{"Kre", "Radial edge coefficient", "N/mm", 110.1, 1e5},
             Coefficient{"Kae", "Axial edge coefficient", "N/mm", -42.4, 1e5},
         })
      s.add_number(c.name, c.doc)
          .with_unit(c.unit)
          .at_least(-c.bound)
          .at_most(c.bound)
          .with_default(c.value);
    s.add_number("element_angle",
                 "Polar-angle size of an edge element; elements are fixed on the tool (a quarter "
                 "circle is divided into equal ones) and an element the CATW cuts counts in part")
        .with_unit("deg")
        .above(0.0009)
        .at_most(10)
        .with_default(0.2);
    return s;
  }
  explicit Armarego(const Params& p)
      : ktc_(p.number("Ktc")),
        krc_(p.number("Krc")),
        kac_(p.number("Kac")),
        kte_(p.number("Kte")),
        kre_(p.number("Kre")),
        kae_(p.number("Kae")),
        elements_(static_cast<std::size_t>(std::ceil(90.0 / p.number("element_angle") - 1e-9))) {}

  // The elements' polar angles are fixed on the tool, so everything that depends on the angle
  // alone (its sine and cosine, the lag's, the edge's stretch) is tabulated once per tool; a
  // sample costs each tooth's rotation and the chip per element, no transcendental function.
  CuttingForce evaluate(const ToolGeometry& tool, const CutState& st) const override {
    const std::shared_ptr<const EdgeTable> table = edge_table(tool);
    const double R = tool.radius(), h = table->step;
    const double sense = st.spindle_rate >= 0 ? 1.0 : -1.0;
    const int teeth = tool.teeth();
    if (teeth > kMaxTeeth) throw std::runtime_error("armarego: more than 64 teeth");
    double tooth_cos[kMaxTeeth], tooth_sin[kMaxTeeth];
    for (int j = 0; j < teeth; ++j) {
      const double angle = tool.tooth_angle(j) + st.spindle_angle;
      tooth_cos[j] = std::cos(angle), tooth_sin[j] = std::sin(angle);
    }
    // Runout: the ball centre is e off the spindle axis towards psi (now) and psi minus a tooth's
    // turn (when the tooth before passed where this one is), so an element at azimuth phi
    // reaches e (cos(psi - phi) - cos(psi_before - phi)) further out than the one before it
    // did, and sin(alpha) of that along its normal: the chip grows or shrinks by as much.
    const double psi = st.spindle_angle + st.runout_angle;
    const double psi_before = psi - sense * 2 * M_PI / teeth;
    const double run_c = st.runout * (std::cos(psi) - std::cos(psi_before));
    const double run_s = st.runout * (std::sin(psi) - std::sin(psi_before));
    const double lo = std::max(0.0, st.alpha_min), hi = std::min(M_PI / 2, st.alpha_max);
    CuttingForce out;
    if (!(hi > lo)) return out;
    const auto first = static_cast<std::size_t>(std::floor(lo / h));
    const auto last = std::min(table->elements.size(), static_cast<std::size_t>(std::ceil(hi / h)));
    double weight = 0, moment = 0;
    for (std::size_t e = first; e < last; ++e) {
      // An element the CATW's end cuts counts for its part inside, taken at that part's middle
      // (the midpoint rule on the clipped element: second order in the element size).
      const double a = static_cast<double>(e) * h, a_lo = std::max(a, lo),
                   a_hi = std::min(a + h, hi);
      if (!(a_hi > a_lo)) continue;
      const bool whole = a_lo == a && a_hi == a + h;
      const Element el = whole ? table->elements[e] : element(tool, 0.5 * (a_lo + a_hi));
      const double db = R * (a_hi - a_lo), ds = db * el.stretch;
      for (int j = 0; j < teeth; ++j) {
        const double cp = tooth_cos[j] * el.cl - tooth_sin[j] * el.sl;
        const double sp = tooth_sin[j] * el.cl + tooth_cos[j] * el.sl;
        const Vec3 n(el.sa * cp, el.sa * sp, -el.ca), m(el.ca * cp, el.ca * sp, el.sa),
            v(-sense * sp, sense * cp, 0);
        const double t =
            st.feed_per_tooth * st.feed_direction.dot(n) + el.sa * (run_c * cp + run_s * sp);
        if (t <= 0) continue;  // not in cut: the element faces away from the feed
        if (st.in_material && !st.in_material(R * n)) continue;  // air: above or already cut
        const double ft = kte_ * ds + ktc_ * t * db, fr = kre_ * ds + krc_ * t * db,
                     fa = kae_ * ds + kac_ * t * db;
        const Vec3 f = -ft * v - fr * n - fa * m;
        out.force += f;
        const double w = f.norm();
        weight += w;
        moment += w * R * (1 - el.ca);  // height of the element above the tip
      }
    }
    out.load_centre = weight > 0 ? moment / weight : 0.0;
    return out;
  }

 private:
  static constexpr int kMaxTeeth = 64;  // the tool schemas' limit
  struct Element {
    double sa, ca;   // sine and cosine of the polar angle at the element's middle
    double cl, sl;   // of the lag there (held below the tool's smallest polar angle)
    double stretch;  // edge length per unit chip width: sqrt(1 + sin^2 a Psi'(a)^2)
  };
  struct EdgeTable {
    const ToolGeometry* tool;
    double fingerprint[6];  // what tells a tool at a reused address from the one tabulated
    double step;
    std::vector<Element> elements;
  };
  // The element at polar angle a (its middle).
  static Element element(const ToolGeometry& tool, double a) {
    const double held = std::max(a, tool.min_polar_angle());  // below it the lag is held
    const double lag = tool.lag(held), slope = std::sin(a) * tool.lag_slope(held);
    return {std::sin(a), std::cos(a), std::cos(lag), std::sin(lag), std::sqrt(1 + slope * slope)};
  }
  static void fingerprint(const ToolGeometry& tool, double* out) {
    out[0] = tool.radius(), out[1] = tool.teeth(), out[2] = tool.min_polar_angle();
    out[3] = tool.lag(0.3), out[4] = tool.lag(1.2), out[5] = tool.lag_slope(0.7);
  }
  // The table for `tool`, built when first asked (or when another tool comes).
  std::shared_ptr<const EdgeTable> edge_table(const ToolGeometry& tool) const {
    double print[6];
    fingerprint(tool, print);
    std::lock_guard<std::mutex> lock(mutex_);
    if (table_ && table_->tool == &tool && std::equal(print, print + 6, table_->fingerprint))
      return table_;
    auto t = std::make_shared<EdgeTable>();
    t->tool = &tool;
    std::copy(print, print + 6, t->fingerprint);
    t->step = M_PI / 2 / static_cast<double>(elements_);
    for (std::size_t e = 0; e < elements_; ++e)
      t->elements.push_back(element(tool, (static_cast<double>(e) + 0.5) * t->step));
    table_ = t;
    return table_;
  }

  double ktc_, krc_, kac_, kte_, kre_, kae_;
  std::size_t elements_;  // over a quarter circle
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const EdgeTable> table_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("armarego", "0.1.0") {
  registrar.add<topomill::ForceModel, topomill::plugins::Armarego>(
      "armarego",
      "Mechanistic ball-end force, Armarego/Lee-Altintas (Eq. 18-21); defaults: "
      "Table 3 of Hao et al.");
}
