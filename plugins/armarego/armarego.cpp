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

  ChipCoefficients chip_coefficients() const override { return {ktc_, krc_, kac_}; }

  // The elements' polar angles are fixed on the tool, so everything that depends on the angle
  // alone (its sine and cosine, the lag's, the edge's stretch) is tabulated once per tool; a
  // sample costs each tooth's rotation and the chip per element, no transcendental function.
  CuttingForce evaluate(const ToolGeometry& tool, const CutState& st) const override {
    const std::shared_ptr<const EdgeTable> table = edge_table(tool);
    const double h = table->step, a0 = table->start;
    const double sense = st.spindle_rate >= 0 ? 1.0 : -1.0;
    const int teeth = tool.teeth();
    if (teeth > kMaxTeeth) throw std::runtime_error("armarego: more than 64 teeth");
    Teeth tt;
    for (int j = 0; j < teeth; ++j) {
      const double angle = tool.tooth_angle(j) + st.spindle_angle;
      tt.cos[j] = std::cos(angle), tt.sin[j] = std::sin(angle);
      // Per-edge runout: edge j is j steps out and up; the edge before it in the spindle's sense
      // (j - 1 turning counter-clockwise) passed the same place its own number of steps out.
      const int before = ((j - static_cast<int>(sense)) % teeth + teeth) % teeth;
      tt.more[j] = j - before;
    }
    // Runout: the ball centre is e off the spindle axis towards psi (now) and psi minus a tooth's
    // turn (when the tooth before passed where this one is), so an element at azimuth phi
    // reaches e (cos(psi - phi) - cos(psi_before - phi)) further out than the one before it
    // did, and sin(alpha) of that along its normal: the chip grows or shrinks by as much.
    const double psi = st.spindle_angle + st.runout_angle;
    const double psi_before = psi - sense * 2 * M_PI / teeth;
    tt.run_c = st.runout * (std::cos(psi) - std::cos(psi_before));
    tt.run_s = st.runout * (std::sin(psi) - std::sin(psi_before));
    const double lo = std::max(a0, st.alpha_min), hi = std::min(M_PI / 2, st.alpha_max);
    Sum sum;
    const auto first = static_cast<std::size_t>(std::max(0.0, std::floor((lo - a0) / h)));
    const auto last =
        std::min(table->elements.size(), static_cast<std::size_t>(std::ceil((hi - a0) / h)));
    for (std::size_t e = first; hi > lo && e < last; ++e) {
      // An element the CATW's end cuts counts for its part inside, taken at that part's middle
      // (the midpoint rule on the clipped element: second order in the element size).
      const double a = a0 + static_cast<double>(e) * h, a_lo = std::max(a, lo),
                   a_hi = std::min(a + h, hi);
      if (!(a_hi > a_lo)) continue;
      const bool whole = a_lo == a && a_hi == a + h;
      const Element el = whole ? table->elements[e] : element(tool, 0.5 * (a_lo + a_hi));
      add(tool, st, el, tool.radius() * (a_hi - a_lo), tt, sum);
    }
    // An end mill's side edge, where the depth of cut reaches above its corner.
    const double side = st.depth_of_cut - tool.radius(), dz = h * tool.reach();
    if (tool.has_bottom() && side > 0 && hi >= M_PI / 2)
      for (double z0 = 0; z0 < side; z0 += dz) {
        const double z1 = std::min(side, z0 + dz);
        add(tool, st, side_element(tool, 0.5 * (z0 + z1)), z1 - z0, tt, sum);
      }
    CuttingForce out;
    out.force = sum.force;
    out.load_centre = sum.weight > 0 ? sum.moment / sum.weight : 0.0;
    return out;
  }

 private:
  static constexpr int kMaxTeeth = 64;  // the tool schemas' limit
  struct Element {
    double sa, ca;   // sine and cosine of the polar angle at the element's middle
    double cl, sl;   // of the lag there (held below the tool's smallest polar angle)
    double stretch;  // edge length per unit chip width: sqrt(1 + (rho Psi'(a) / r)^2)
    // A side element's height above the tube's centre plane (sa = 1, ca = 0); -1 on the tube.
    double up = -1;
  };
  struct Teeth {
    double cos[kMaxTeeth], sin[kMaxTeeth];
    int more[kMaxTeeth];  // per-edge runout steps beyond the edge before
    double run_c = 0, run_s = 0;
  };
  struct Sum {
    Vec3 force = Vec3::Zero();
    double weight = 0, moment = 0;
  };

  // One element's force on every tooth, added to `sum`; db is its chip width.
  void add(const ToolGeometry& tool, const CutState& st, const Element& el, double db,
           const Teeth& tt, Sum& sum) const {
    const double R = tool.radius(), ring = tool.ring(), sense = st.spindle_rate >= 0 ? 1.0 : -1.0;
    const double ds = db * el.stretch;
    const bool per_edge = st.edge_radial != 0 || st.edge_axial != 0;
    for (int j = 0; j < tool.teeth(); ++j) {
      const double cp = tt.cos[j] * el.cl - tt.sin[j] * el.sl;
      const double sp = tt.sin[j] * el.cl + tt.cos[j] * el.sl;
      const Vec3 n(el.sa * cp, el.sa * sp, -el.ca), m(el.ca * cp, el.ca * sp, el.sa),
          v(-sense * sp, sense * cp, 0);
      double t =
          st.feed_per_tooth * st.feed_direction.dot(n) + el.sa * (tt.run_c * cp + tt.run_s * sp);
      if (per_edge) t += tt.more[j] * (st.edge_radial * el.sa - st.edge_axial * el.ca);
      if (t <= 0) continue;  // not in cut: the element faces away from the feed
      if (st.in_material) {
        // The element's place from the tube's centre on the axis: R n on a ball, as it was.
        Vec3 place = el.up >= 0 ? Vec3(tool.reach() * cp, tool.reach() * sp, el.up) : Vec3(R * n);
        if (el.up < 0 && ring > 0) place += Vec3(ring * cp, ring * sp, 0);
        if (per_edge) place += j * Vec3(st.edge_radial * cp, st.edge_radial * sp, st.edge_axial);
        if (!st.in_material(place)) continue;  // air: above or already cut
      }
      const double ft = kte_ * ds + ktc_ * t * db, fr = kre_ * ds + krc_ * t * db,
                   fa = kae_ * ds + kac_ * t * db;
      const Vec3 f = -ft * v - fr * n - fa * m;
      sum.force += f;
      const double w = f.norm();
      sum.weight += w;
      // The element's height above the tip.
      sum.moment += el.up >= 0 ? w * (R + el.up) : w * R * (1 - el.ca);
    }
  }

  struct EdgeTable {
    const ToolGeometry* tool;
    double fingerprint[7];  // what tells a tool at a reused address from the one tabulated
    double step, start;     // the elements' size and where the first begins (rad)
    std::vector<Element> elements;
  };
  // The element at polar angle a (its middle). Its edge runs rho = c + r sin(a) from the axis.
  static Element element(const ToolGeometry& tool, double a) {
    const double held = std::max(a, tool.min_polar_angle());  // below it the lag is held
    const double lag = tool.lag(held),
                 slope = (std::sin(a) + tool.ring() / tool.radius()) * tool.lag_slope(held);
    return {std::sin(a), std::cos(a), std::cos(lag), std::sin(lag), std::sqrt(1 + slope * slope)};
  }
  // A side element at height z: a helix of lead side_lead() on the cylinder of radius reach().
  static Element side_element(const ToolGeometry& tool, double z) {
    const double lag = tool.lag(M_PI / 2) - tool.side_lead() * z;
    const double slope = tool.reach() * tool.side_lead();
    return {1.0, 0.0, std::cos(lag), std::sin(lag), std::sqrt(1 + slope * slope), z};
  }
  static void fingerprint(const ToolGeometry& tool, double* out) {
    out[0] = tool.radius(), out[1] = tool.teeth(), out[2] = tool.min_polar_angle();
    out[3] = tool.lag(0.3), out[4] = tool.lag(1.2), out[5] = tool.lag_slope(0.7);
    out[6] = tool.ring();
  }
  // The table for `tool`, built when first asked (or when another tool comes). Elements of a
  // quarter circle's 1 / elements_ from the edge's start; none on a sharp corner (r = 0).
  std::shared_ptr<const EdgeTable> edge_table(const ToolGeometry& tool) const {
    double print[7];
    fingerprint(tool, print);
    std::lock_guard<std::mutex> lock(mutex_);
    if (table_ && table_->tool == &tool && std::equal(print, print + 7, table_->fingerprint))
      return table_;
    auto t = std::make_shared<EdgeTable>();
    t->tool = &tool;
    std::copy(print, print + 7, t->fingerprint);
    t->step = M_PI / 2 / static_cast<double>(elements_);
    t->start = tool.first_polar_angle();
    const auto n = tool.radius() > 0
                       ? static_cast<std::size_t>(std::ceil((M_PI / 2 - t->start) / t->step - 1e-9))
                       : 0;
    for (std::size_t e = 0; e < n; ++e)
      t->elements.push_back(element(tool, t->start + (static_cast<double>(e) + 0.5) * t->step));
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
