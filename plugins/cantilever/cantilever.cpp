// Static tool deflection: the tool as a cantilever clamped in the holder, loaded at the cutting
// force's centre (docs/model.md Eq. 27-28).
#include <algorithm>
#include <cmath>

#include "topomill/deformation.hpp"
#include "topomill/error.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

// Deflection at distance s from the clamp under a load F at distance sF from it:
//   s <= sF: F s^2 (3 sF - s) / (6 E I);   s >= sF: F sF^2 (3 s - sF) / (6 E I)
// (Eq. 27 is the second). The surface is generated at the contact point, R (1 - cos lambda)
// above the tip. I = pi De^4 / 64 with the effective diameter of a fluted tool, De = ratio x D.
class Cantilever : public Deformation {
 public:
  static Schema schema() {
    Schema s;
    s.add_number("overhang",
                 "Overhang L of the tool out of the holder (Table 1's tool is 75 mm long)")
        .with_unit("mm")
        .above(0)
        .with_default(40.0);
    s.add_number("young_modulus", "Young's modulus E of the tool (carbide 550-620 GPa)")
        .with_unit("GPa")
        .above(0)
        .with_default(580.0);
    s.add_number("diameter_ratio",
                 "Effective diameter over nominal, De / D (fluted: ~0.8, Kops & Vo)")
        .above(0)
        .at_most(1)
        .with_default(0.8);
    return s;
  }
  explicit Cantilever(const Params& p)
      : overhang_(p.number("overhang")),
        e_(p.number("young_modulus") * 1e3),  // N/mm^2
        ratio_(p.number("diameter_ratio")) {}

  // Deflection (mm) per newton at distance s from the clamp, load at sF.
  double compliance(double s, double sF, double ei) const {
    return s <= sF ? s * s * (3 * sF - s) / (6 * ei) : sF * sF * (3 * s - sF) / (6 * ei);
  }

  Vec3 correction(const CuttingForce& f, const ToolGeometry& tool,
                  const CutState& st) const override {
    const double R = tool.radius();
    if (overhang_ <= R)
      throw ParamError("overhang", "the overhang must exceed the ball radius " + format_number(R) +
                                       " mm: the ball has to stand out of the holder");
    // The shank's diameter is the cutter's (2 reach: 2 R for a ball, D for an end mill or face
    // mill); the contact is r (1 - cos) above the tip on the tube of radius r.
    const double de = ratio_ * 2 * tool.reach();
    const double ei = e_ * M_PI * std::pow(de, 4) / 64;
    const double z = R * (1 - std::cos(st.inclination));
    const double s = overhang_ - z, sF = overhang_ - std::clamp(f.load_centre, 0.0, overhang_);
    const double c = compliance(s, sF, ei);
    return {c * f.force.x(), c * f.force.y(), 0.0};
  }

 private:
  double overhang_, e_, ratio_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("cantilever", "0.1.0") {
  registrar.add<topomill::Deformation, topomill::plugins::Cantilever>(
      "cantilever", "Tool deflection as a cantilever beam loaded at the force centre (Eq. 27-28)");
}
